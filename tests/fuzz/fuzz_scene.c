/* libFuzzer target: the scene reader and builder. Any input must end in a
 * scene or in a one-line "FILE:LINE:COLUMN: message" — never a crash, a
 * leak or undefined behaviour. A scene that loads is also simulated for a
 * few steps, so the builder's callbacks see what the reader accepted. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "braun.h"
#include "braun_scene_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[512];
    braun_scene_file *f = braun_scene_load_text("fuzz.json", (const char *)data, size, err, sizeof err);
    if (!f) {
        /* the message is one line that names the place */
        if (strncmp(err, "fuzz.json:", 10) != 0 || strchr(err, '\n')) abort();
        return 0;
    }
    braun_model model;
    if (braun_model_init(&model, &f->sys) == BRAUN_OK) {
        model.opt.corrections = f->corrections;
        size_t bytes = braun_data_size(&model);
        void *buf = bytes < (64u << 20) ? malloc(bytes) : NULL;
        braun_data d;
        if (buf && braun_data_init(&d, &model, buf, bytes) == BRAUN_OK &&
            braun_set_state(&d, 0, f->q0, f->v0) == BRAUN_OK)
            (void)braun_integrate(&d, BRAUN_RK4, 1e-3, 5e-3, 1, NULL, NULL);
        free(buf);
    }
    braun_scene_free(f);
    return 0;
}
