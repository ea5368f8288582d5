/* braun --help, and a command's --help. */
#include <string.h>

#include "braun_cli.h"

/* --rank-tol's default is this build's (braun_default_rank_tol): the
 * float build's help gave double's. */
#ifdef BRAUN_SINGLE
#define RANK_TOL_DEFAULT "30*sqrt(eps) = 0.0104 in\n                         this float build"
#else
#define RANK_TOL_DEFAULT "10*max(rows, n)*eps"
#endif

int braun_cli_help_asked(const char *cmd, int argc, char **argv)
{
    int at = -1;
    for (int i = 0; i < argc && at < 0; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) at = i;
    if (at < 0) return 0;
    if (argc > 1)
        return braun_cli_error("%s %s takes no other arguments (got '%s'): braun %s %s alone "
                               "shows the usage", cmd, argv[at], argv[at == 0 ? 1 : 0], cmd,
                               argv[at]);
    braun_cli_usage(stdout);
    return -1;
}

void braun_cli_usage(FILE *f)
{
    fputs(
"Usage: braun run MODEL --dt H --t-end T [options]\n"
"       braun plot MODEL --dt H --t-end T [options] -o FILE.svg|.html|.png\n"
"       braun plot MODEL --traj CSV -o FILE [plot options]\n"
"       braun check SCENE\n"
"       braun gen chain N [--rods] [--angle DEG] [-o FILE]\n"
"       braun gen ladder N [--angle DEG] [-o FILE]\n"
"       braun gen n-four-bar N [-o FILE]\n"
"       braun gen spatial-chain N [--angle DEG] [-o FILE]\n"
"       braun gen-c SCENE [--symbol NAME] [-o FILE] [--header FILE]\n"
"       braun list\n"
"       braun --help | --version | COMMAND --help (nothing after them)\n"
"\n"
"Simulates a constrained mechanical system with the corrected equation of\n"
"motion of Braun & Goldfarb (2012), Eqs. 16, 17 and 20, and reports its\n"
"constraint, energy and trajectory errors.\n"
"\n"
"Commands:\n"
"  run MODEL              integrate MODEL from its initial state to T and write a\n"
"                         JSON summary; MODEL is a built-in model (see 'braun\n"
"                         list') or a scene file (any name ending in .json or\n"
"                         containing '/'; docs/scene-format.md); a shipped\n"
"                         scene runs by its name from any directory\n"
"                         (four-bar.json, damped-motor)\n"
"  plot MODEL             run MODEL as 'run' does and draw it: FILE.svg a\n"
"                         stroboscopic view (configurations over time, earlier\n"
"                         ones fainter, paths of --points), FILE.html a\n"
"                         self-contained animation (play/pause, time slider),\n"
"                         FILE.png the same through gnuplot; --plot draws\n"
"                         coordinates against time instead; --traj CSV draws a\n"
"                         trajectory written by 'run --out' without running\n"
"  check SCENE            read and build a scene (or a built-in model) and print\n"
"                         n, m, p, the rank of its rows at t = 0 (redundant rows,\n"
"                         degrees of freedom), its initial residuals, whether\n"
"                         its rows can all hold (consistent: yes | no: then the\n"
"                         joints that disagree are named and it exits 1), its\n"
"                         energy law and corrections, one 'key: value' per line\n"
"  gen chain N            write an N-link pendulum chain scene (rigid links, or\n"
"                         uniform rods with --rods), N <= 2000, straight and\n"
"                         --angle DEG below the horizontal (default 0), at rest,\n"
"                         to stdout or -o FILE\n"
"  gen ladder N           write a closed-loop ladder: three rails of N rigid\n"
"                         links 0.5 m apart and N rungs pinned to them at both\n"
"                         ends and the middle (n = m = 12N, rank 11N: one\n"
"                         redundant row per cell), N <= 2000, rails --angle DEG\n"
"                         from the vertical (default 30), at rest\n"
"  gen n-four-bar N       write IFToMM benchmark A02: N four-bar windows of\n"
"                         2N + 1 uniform rods, singular when horizontal, N <= 2000\n"
"  gen spatial-chain N    write N rigid3d bars on spherical joints (n = 7N, m = 4N),\n"
"                         straight --angle DEG below the horizontal, turning\n"
"                         about the vertical at 1 rad/s, N <= 2000\n"
"  gen-c SCENE            write the scene as C99 that defines it statically, for\n"
"                         firmware (no parser, no allocation; docs/firmware.md);\n"
"                         --header FILE also writes its declarations; the\n"
"                         symbol prefix is --symbol NAME, or the file name\n"
"                         without .json: kept if a C identifier, '-' and '.'\n"
"                         made '_' (noted on stderr); any other character, a\n"
"                         first character not a letter, or over 48 characters:\n"
"                         refused, give --symbol (docs/cli.md)\n"
"  list                   built-in models, one per line: name, n, m, p,\n"
"                         description; then the shipped scenes and their place\n"
"\n",
        f);
    /* Two literals: C99 compilers need only support 4095 characters in one. */
    fputs(
"Options of run:\n"
"  --dt H                 step size, > 0 (dopri5: first trial step)\n"
"  --t-end T              end time, > 0\n"
"  --integrator NAME      euler | heun | rk4 | dopri5 (default rk4);\n"
"                         dopri5 is adaptive and reports every accepted step\n"
"  --corrections LIST     comma list of position,velocity,energy, or all | none\n"
"                         (default: what the scene declares; every correction a\n"
"                         built-in model supports; all: every one supported)\n"
"  --discretization D     per-step | per-stage (default per-step; dopri5 is\n"
"                         always per-step)\n"
"  --rank-tol X           relative rank tolerance of the pseudoinverses,\n"
"                         0 <= X < 1 (default 0: " RANK_TOL_DEFAULT ")\n"
"  --energy-max-rel X     largest relative velocity change of one step's energy\n"
"                         correction (default 0: 0.01)\n"
"  --guard X              accuracy guard: stop with BRAUN_ERR_ACCURACY, keeping\n"
"                         the last state that passed, when a residual exceeds X\n"
"                         times its scale (default 0: 1e-3; < 0: off)\n"
"  --soft-tol X           soft-direction filter of redundant rows near singular\n"
"                         configurations: directions whose singular value is\n"
"                         below 10 X |C| (X < 1) take their acceleration from\n"
"                         continuity (default 0: 1e-4; < 0: off; docs/method.md)\n"
"  --rtol X, --atol X     dopri5 error tolerances (default 1e-8, 1e-10)\n"
"  --max-steps N          step limit, a whole number >= 1 (default 1e8): dopri5\n"
"                         stops with BRAUN_ERR_TOO_MANY_STEPS after N attempts;\n"
"                         a fixed-step run of more than N steps (T/H) is\n"
"                         refused before it starts (exit 2)\n"
"  --out FILE             trajectory CSV (- for stdout): t, the coordinates and\n"
"                         velocities named from the scene (crank.x [m],\n"
"                         crank.omega [rad/s]; q[i], v[i] without one), pos_err,\n"
"                         vel_err, energy_err, traj_err; units in the header\n"
"  --every K              CSV row every K steps (default 1; needs --out); the\n"
"                         last state is always written\n"
"  --summary FILE         JSON summary to FILE, - for stdout (default -)\n"
"  --ref-h X              substep of the integrated reference solution\n"
"                         (default 1e-4)\n"
"  --backend NAME         linear algebra: dense (default: libbraun's kernels) |\n"
"                         lapack | suitesparse | auto (by size and sparsity);\n"
"                         suitesparse and auto use the scene's sparsity when it\n"
"                         has one; the summary names the backend used\n"
"  --sparse               hand the solver the scene's sparsity (a scene file\n"
"                         without rods): block-diagonal M, sparse rows; needed\n"
"                         above 4096 coordinates or rows\n"
"  --progress, --quiet    a progress line on stderr (time, steps, rate, time\n"
"                         left) and a closing summary line: shown by default\n"
"                         when stderr is a terminal; --progress forces them,\n"
"                         --quiet turns them off (errors are always shown)\n"
"\n",
        f);
    fputs(
"Options of plot (besides those of run; --summary only if given):\n"
"  -o FILE                the picture: .svg, .html or .png\n"
"  --points A,B           trace these points: body.point (crank.A), a body's\n"
"                         centre (rod), ground.NAME, a reported point (tip)\n"
"  --plot X,Y             coordinates against time: any column of the CSV\n"
"                         (crank.theta, rod.vx, pos_err, q[2], a reported\n"
"                         point's tip.x), POINT.x / .y / .z, or x, y of every\n"
"                         --points point\n"
"  --from T               draw from time T on (default: the start)\n"
"  --frames K             configurations drawn (default 12; .html: 400)\n"
"  --samples N            states kept for paths and charts (default 2000)\n"
"  --view PLANE           projection: xy (default), xz, yz, yx, zx, zy\n"
"  --traj CSV             draw a trajectory written by 'braun run MODEL --out';\n"
"                         a value that is not a finite number (nan, inf,\n"
"                         1e999) or underflows (1e-400) is refused at\n"
"                         CSV:LINE with its column\n"
"\n"
"A picture whose numbers would not be finite (points spanning more than a\n"
"double: 1e308 and -1e308) is refused and nothing written: exit 2 with --traj,\n"
"1 after a run.\n"
"\n"
"The errors are the maxima over every step, including t = 0, of ||Phi_q||,\n"
"||[dPhi_q/dt; Phi_v]||, |Phi_e| and ||q - q_ref|| against the model's exact\n"
"reference. cpu_s is the integration alone, measured in a separate run without\n"
"monitoring. Units of every CSV column and JSON key: docs/cli.md.\n"
"\n"
"A scene file that cannot be read is reported as one line\n"
"'braun: FILE:LINE:COLUMN: message' and nothing is simulated. Outputs\n"
"(--out, --summary, -o) are regular files, character devices such as\n"
"/dev/null, or - (stdout); FIFOs, directories and sockets are refused, and so\n"
"are two outputs that are one file and an output that is the input scene.\n"
"\n"
"Exit status: 0 success; 1 the solver failed (message on stderr, summary and\n"
"CSV written up to the last good step), the library refused the system, check\n"
"found constraints with no solution at t = 0, or an output could not be\n"
"written; 2 bad arguments or a bad scene file.\n",
        f);
}
