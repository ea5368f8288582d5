/* The reference solution of Andrews' mechanism (braun_models.h) from the
 * Test Set for IVP Solvers: an oracle, host tier. */
#include "braun_reference.h"

/* andrews.f, andsoln: y(1..7) at t = 0.03. */
const double braun_andrews_q_ref[7] = {0.1581077119629904e+2, -0.1575637105984298e+2,
                                       0.4082224013073101e-1, -0.5347301163226948e+0,
                                       0.5244099658805304e+0, 0.5347301163226948e+0,
                                       0.1048080741042263e+1};
