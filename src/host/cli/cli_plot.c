#include "braun_cli.h"
int braun_cli_plot(int argc, char **argv) { (void)argc; (void)argv; return braun_cli_error("plot: todo"); }
