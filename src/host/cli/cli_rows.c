/* Which element of a scene file owns a row of [Φ_q; Φ_v]. The library
 * names rows by their index (an inconsistency's two rows,
 * d->error.index/index2); people know the joints. A scene numbers its
 * holonomic rows rods first, then holonomic joints in file order (each its
 * class's rows), then the bodies' own rows (a rigid3d's unit quaternion) in
 * body order; after them the nonholonomic joints' rows, in file order
 * (braun_scene_build). */
#include <stdio.h>

#include "braun_cli.h"

const char *braun_cli_row_owner(const braun_scene_file *sf, int row, char *buf, size_t size)
{
    if (!sf || row < 0 || row >= sf->scene.m + sf->scene.p) return NULL;
    const braun_scene *s = &sf->scene;
    if (row >= s->m) {
        /* Φ_v's rows (rows m.. of [A_q; A_vv]): the nonholonomic joints,
         * numbered among themselves. */
        for (int k = 0; k < s->njoints; k++) {
            const braun_scene_joint *j = &s->joints[k];
            if (!j->type->nonholonomic || row - s->m < j->row ||
                row - s->m >= j->row + j->type->rows(j))
                continue;
            const char *name = sf->joint_names ? sf->joint_names[k] : NULL;
            if (name) snprintf(buf, size, "joint '%s' (%s)", name, j->type->name);
            else snprintf(buf, size, "joint #%d (%s)", k + 1, j->type->name);
            return buf;
        }
        return NULL;
    }
    for (int k = 0; k < s->nrods; k++)
        if (s->rods[k].row == row) {
            snprintf(buf, size, "rod #%d", k + 1);
            return buf;
        }
    for (int k = 0; k < s->njoints; k++) {
        const braun_scene_joint *j = &s->joints[k];
        if (j->type->nonholonomic || row < j->row || row >= j->row + j->type->rows(j)) continue;
        const char *name = sf->joint_names ? sf->joint_names[k] : NULL;
        if (name) snprintf(buf, size, "joint '%s' (%s)", name, j->type->name);
        else snprintf(buf, size, "joint #%d (%s)", k + 1, j->type->name);
        return buf;
    }
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *b = &s->bodies[k];
        if (row < b->row || row >= b->row + b->kind->rows) continue;
        const char *name = sf->body_names ? sf->body_names[k] : NULL;
        if (name) snprintf(buf, size, "body '%s' (%s: its own constraint)", name, b->kind->name);
        else snprintf(buf, size, "body #%d (%s: its own constraint)", k + 1, b->kind->name);
        return buf;
    }
    return NULL;
}
