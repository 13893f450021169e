/* A C integrator that never returns and ignores SIGINT and SIGTERM: only SIGKILL ends it. */
#include <signal.h>
#include <stddef.h>

int integrate(const double *gyro, const double *accel, size_t n_samples, size_t samples_per_step, double *rotation, double *velocity)
{
    volatile unsigned long spin = 0;
    signal(SIGINT, SIG_IGN);
    signal(SIGTERM, SIG_IGN);
    for (;;)
        spin++;
    return 0;
}
