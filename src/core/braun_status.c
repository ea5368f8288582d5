/* Names of the status codes. */
#include "braun.h"

const char *braun_status_str(int status)
{
    switch (status) {
    case BRAUN_OK: return "BRAUN_OK: success";
    case BRAUN_STOPPED: return "BRAUN_STOPPED: the output callback asked to stop";
    case BRAUN_ERR_ARGUMENT: return "BRAUN_ERR_ARGUMENT: invalid argument, option or claim (a NULL pointer, an unknown option, a false BRAUN_MASS_CONSTANT or BRAUN_SCLERONOMIC, a wrong callback): braun_error_format or the check's report says which";
    case BRAUN_ERR_SIZE: return "BRAUN_ERR_SIZE: invalid or inconsistent sizes n, m, p";
    case BRAUN_ERR_BUFFER: return "BRAUN_ERR_BUFFER: workspace buffer smaller than braun_data_size(), or a backend could not allocate";
    case BRAUN_ERR_NONFINITE: return "BRAUN_ERR_NONFINITE: NaN or Inf in the state or a callback output";
    case BRAUN_ERR_MASS_NOT_SYMMETRIC: return "BRAUN_ERR_MASS_NOT_SYMMETRIC: mass matrix is not symmetric";
    case BRAUN_ERR_MASS_NOT_SPD: return "BRAUN_ERR_MASS_NOT_SPD: mass matrix is not positive definite";
    case BRAUN_ERR_CALLBACK: return "BRAUN_ERR_CALLBACK: a callback reported a fatal failure";
    case BRAUN_ERR_CALLBACK_RECOVERABLE: return "BRAUN_ERR_CALLBACK_RECOVERABLE: a callback failed recoverably and the step could not be retried";
    case BRAUN_ERR_STEP: return "BRAUN_ERR_STEP: step size must be finite and positive";
    case BRAUN_ERR_TIME: return "BRAUN_ERR_TIME: t_end must be finite and after the current time";
    case BRAUN_ERR_DIVERGED: return "BRAUN_ERR_DIVERGED: the solution left the finite range (step too large?)";
    case BRAUN_ERR_STEP_TOO_SMALL: return "BRAUN_ERR_STEP_TOO_SMALL: adaptive step fell below its minimum";
    case BRAUN_ERR_TOO_MANY_STEPS: return "BRAUN_ERR_TOO_MANY_STEPS: step limit reached before t_end";
    case BRAUN_ERR_MISSING_CALLBACK: return "BRAUN_ERR_MISSING_CALLBACK: a callback the sizes or flags require is NULL";
    case BRAUN_ERR_INCONSISTENT: return "BRAUN_ERR_INCONSISTENT: dependent constraint rows disagree: the constraints have no solution here";
    case BRAUN_ERR_TIME_RESOLUTION: return "BRAUN_ERR_TIME_RESOLUTION: the step cannot advance time in this precision (t + h rounds to t or far from it)";
    case BRAUN_ERR_ACCURACY: return "BRAUN_ERR_ACCURACY: the residuals exceed the accuracy guard";
    case BRAUN_ERR_NO_ENERGY_LAW: return "BRAUN_ERR_NO_ENERGY_LAW: energy correction requested but the system has no energy law";
    default: return "BRAUN_UNKNOWN: unknown status code";
    }
}
