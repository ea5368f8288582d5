/* Inside the Simbody plugin (C++): the model both of its files build,
 * planar (cmp_simbody.cpp) or spatial (cmp_simbody3.cpp). */
#ifndef CMP_SIMBODY_MODEL_H
#define CMP_SIMBODY_MODEL_H

#include <cstddef>
#include <vector>

#include <Simbody.h>

#include "cmp_simbody_plugin.h"

namespace cmp_sb {

/* The harness (cmp_simbody_plugin.h), set when the plugin is loaded. */
extern const cmp_sb_host *H;

struct Model {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter;
    SimTK::GeneralForceSubsystem forces;
    cmp_mech *mech;                          /* the host's; its tree chosen by prepare() */
    std::vector<SimTK::MobilizedBody> mob;   /* per link (spatial: per body) */
    std::vector<SimTK::MobilizedBody> mid;   /* per link: the massless frame between it and
                                              * its parent, or an empty handle */
    SimTK::State state;                      /* the initial state, q and u set */

    explicit Model(cmp_mech *m) : system(), matter(system), forces(system), mech(m) {}
    Model(const Model &) = delete;
    Model &operator=(const Model &) = delete;

    SimTK::MobilizedBody &body(int l) { return l < 0 ? matter.updGround() : mob[(size_t)l]; }
};

/* cmp_simbody3.cpp, for m->spatial: the tree and what Simbody cannot take
 * (0, or -1 with why); the mobilizers, constraints, forces and initial
 * state of M (M.mob sized); libbraun's q, v from a state realized through
 * Velocity (pose: scratch of 13 per body; q holds the previous sample:
 * each quaternion keeps its sign; spatial_seed sets the initial ones). */
int spatial_prepare(cmp_mech3 *m, char *why, size_t whysize);
void spatial_build(Model &M, bool ball_only);
void spatial_seed(const cmp_mech3 *m, double *q);
void spatial_sample(const Model &M, const SimTK::State &s, double *pose, double *q, double *v);

} // namespace cmp_sb

#endif
