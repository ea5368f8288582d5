/* Heap-call counter by interposition, for tests of code whose allocations
 * happen inside shared libraries (CHOLMOD, SPQR, LAPACK), which the
 * link-time --wrap of tests/heap_count.h cannot see: the executable's
 * malloc family replaces glibc's (its documented interposition) and counts.
 * Not under AddressSanitizer, which brings its own allocator; valgrind
 * replaces these too (heap_counting() says whether the counters see the
 * program's allocations). Include in one test file only. */
#ifndef BRAUN_TEST_HEAP_INTERPOSE_H
#define BRAUN_TEST_HEAP_INTERPOSE_H

#include <stddef.h>
#include <stdlib.h>

/* volatile: GCC assumes malloc() touches no program globals. */
static volatile long heap_calls, heap_allocs, heap_frees;

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
void *__libc_malloc(size_t size);
void *__libc_calloc(size_t n, size_t size);
void *__libc_realloc(void *p, size_t size);
void __libc_free(void *p);
void *malloc(size_t size)
{
    heap_calls++;
    heap_allocs++;
    return __libc_malloc(size);
}
void *calloc(size_t n, size_t size)
{
    heap_calls++;
    heap_allocs++;
    return __libc_calloc(n, size);
}
void *realloc(void *p, size_t size)
{
    heap_calls++;
    return __libc_realloc(p, size);
}
void free(void *p)
{
    heap_calls++;
    if (p) heap_frees++;
    __libc_free(p);
}
#endif

/* Whether the counters above see this program's allocations. */
static int heap_counting(void)
{
    /* Through pointers: a direct call could be inlined from this file and
     * miss what replaces the symbol (valgrind). */
    void *(*volatile alloc)(size_t) = malloc;
    void (*volatile release)(void *) = free;
    const long before = heap_allocs;
    release(alloc(16));
    return heap_allocs > before;
}

#endif
