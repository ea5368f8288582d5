/* Heap-call counter for tests linked with
 * -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free (see the
 * LDFLAGS_<test> lines in the Makefile and mk/scenes.mk): every call that
 * reaches the C library's allocator increments heap_calls. Include in one
 * test file only. */
#ifndef BRAUN_TEST_HEAP_COUNT_H
#define BRAUN_TEST_HEAP_COUNT_H

#include <stddef.h>

void *__real_malloc(size_t size);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t size);
void __real_free(void *p);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t size);
void __wrap_free(void *p);

/* volatile: GCC assumes malloc() touches no program globals. */
static volatile long heap_calls;

void *__wrap_malloc(size_t size) { heap_calls++; return __real_malloc(size); }
void *__wrap_calloc(size_t n, size_t size) { heap_calls++; return __real_calloc(n, size); }
void *__wrap_realloc(void *p, size_t size) { heap_calls++; return __real_realloc(p, size); }
void __wrap_free(void *p) { heap_calls++; __real_free(p); }

#endif
