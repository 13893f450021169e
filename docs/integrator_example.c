/*
 * A coning and sculling integrator in C, with the signature that
 * strapdown.analysis.coning.integrators.adapters.compiled() calls through ctypes:
 *
 *   int integrate(const double *gyro, const double *accel, size_t n_samples,
 *                 size_t samples_per_step, double *rotation, double *velocity);
 *
 * gyro, accel:   n_samples x 3, row-major: the increments of each sample [rad], [m/s];
 * rotation:      (n_samples / samples_per_step) x 3: the rotation vector of each step [rad];
 * velocity:      the same rows: the velocity increment of each step, body axes at the
 *                start of the step [m/s];
 * accel and velocity are NULL for a coning-only call.  Every call starts from rest;
 * the function returns 0 on success.
 *
 * The integrator is Savage's per-sample recursion (Savage 1998, part 1, section 7.1.2;
 * part 2 for sculling), one sample at a time as flight code runs it:
 *
 *   beta  += 1/2 (alpha + dalpha_prev/6) x dalpha
 *   gamma += 1/2 [(alpha + dalpha_prev/6) x dnu + (nu + dnu_prev/6) x dalpha]
 *   alpha += dalpha,   nu += dnu
 *
 * and at the end of a step  rotation = alpha + beta,  velocity = nu + 1/2 alpha x nu + gamma.
 *
 * Build:  cc -O2 -shared -fPIC -o libintegrator.so docs/integrator_example.c
 */
#include <stddef.h>

static void cross_add(double *out, const double *a, const double *b, double scale)
{
    out[0] += scale * (a[1] * b[2] - a[2] * b[1]);
    out[1] += scale * (a[2] * b[0] - a[0] * b[2]);
    out[2] += scale * (a[0] * b[1] - a[1] * b[0]);
}

int integrate(const double *gyro, const double *accel, size_t n_samples, size_t samples_per_step, double *rotation, double *velocity)
{
    double alpha[3] = {0}, beta[3] = {0}, nu[3] = {0}, gamma[3] = {0};
    double last[3] = {0}, last_b[3] = {0}, a_read[3], n_read[3];
    size_t k, i, step = 0;

    if (gyro == NULL || rotation == NULL || samples_per_step == 0 || n_samples % samples_per_step != 0)
        return 1;
    if ((accel == NULL) != (velocity == NULL))
        return 2;
    for (k = 0; k < n_samples; k++) {
        const double *d = gyro + 3 * k;
        const double *db = accel != NULL ? accel + 3 * k : NULL;
        for (i = 0; i < 3; i++) {
            a_read[i] = alpha[i] + last[i] / 6.0;
            n_read[i] = nu[i] + last_b[i] / 6.0;
        }
        cross_add(beta, a_read, d, 0.5);
        if (db != NULL) {
            cross_add(gamma, a_read, db, 0.5);
            cross_add(gamma, n_read, d, 0.5);
        }
        for (i = 0; i < 3; i++) {
            alpha[i] += d[i];
            last[i] = d[i];
            if (db != NULL) {
                nu[i] += db[i];
                last_b[i] = db[i];
            }
        }
        if ((k + 1) % samples_per_step == 0) {
            for (i = 0; i < 3; i++)
                rotation[3 * step + i] = alpha[i] + beta[i];
            if (velocity != NULL) {
                double *v = velocity + 3 * step;
                for (i = 0; i < 3; i++)
                    v[i] = nu[i] + gamma[i];
                cross_add(v, alpha, nu, 0.5);
            }
            for (i = 0; i < 3; i++)
                alpha[i] = beta[i] = nu[i] = gamma[i] = 0.0;
            step++;
        }
    }
    return 0;
}
