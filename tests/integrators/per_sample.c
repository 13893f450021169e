/* Savage's per-sample recursion behind a per-sample C API with global state:
 *   void sav_reset(void); void sav_put(const double gyro[3]); void sav_get(double rotation[3]); */
static double alpha[3], beta[3], last[3];

void sav_reset(void)
{
    for (int i = 0; i < 3; i++)
        alpha[i] = beta[i] = last[i] = 0.0;
}

void sav_put(const double *d)
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = alpha[i] + last[i] / 6.0;
    beta[0] += 0.5 * (r[1] * d[2] - r[2] * d[1]);
    beta[1] += 0.5 * (r[2] * d[0] - r[0] * d[2]);
    beta[2] += 0.5 * (r[0] * d[1] - r[1] * d[0]);
    for (int i = 0; i < 3; i++) {
        alpha[i] += d[i];
        last[i] = d[i];
    }
}

void sav_get(double *rotation)
{
    for (int i = 0; i < 3; i++) {
        rotation[i] = alpha[i] + beta[i];
        alpha[i] = beta[i] = 0.0;
    }
}
