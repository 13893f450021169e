/*
 * PX4's IntegratorConing written again in C from its description (see px4_integrator_coning.py),
 * float32, one rate sample per call, with global state: the per-sample API
 *   void px4_reset(void); void px4_put(const double rate[3]); void px4_get(double integral[3]);
 */
static const float DT = 0.001f;
static float alpha[3], beta[3], last_alpha[3], last_delta_alpha[3], last_val[3];

void px4_reset(void)
{
    for (int i = 0; i < 3; i++)
        alpha[i] = beta[i] = last_alpha[i] = last_delta_alpha[i] = last_val[i] = 0.0f;
}

void px4_put(const double *rate)
{
    float val[3], d[3], r[3];
    for (int i = 0; i < 3; i++) {
        val[i] = (float)rate[i];
        d[i] = (val[i] + last_val[i]) * DT * 0.5f;
        last_val[i] = val[i];
        r[i] = last_alpha[i] + last_delta_alpha[i] * (1.0f / 6.0f);
    }
    beta[0] += (r[1] * d[2] - r[2] * d[1]) * 0.5f;
    beta[1] += (r[2] * d[0] - r[0] * d[2]) * 0.5f;
    beta[2] += (r[0] * d[1] - r[1] * d[0]) * 0.5f;
    for (int i = 0; i < 3; i++) {
        last_delta_alpha[i] = d[i];
        last_alpha[i] = alpha[i];
        alpha[i] += d[i];
    }
}

void px4_get(double *integral)
{
    for (int i = 0; i < 3; i++) {
        integral[i] = (double)(alpha[i] + beta[i]);
        alpha[i] = beta[i] = last_alpha[i] = 0.0f;
    }
}
