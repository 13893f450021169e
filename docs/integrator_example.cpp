/*
 * A coning integrator written as a C++ class, one sample at a time, and the
 * extern "C" shim through which
 * strapdown.analysis.coning.integrators.adapters.per_sample_library() calls it:
 *
 *   void *integrator_create(void);                     new object
 *   void  integrator_destroy(void *);                  delete it
 *   void  integrator_reset(void *);                    clear every state: a new record
 *   void  integrator_put(void *, const double gyro[3]); one sample's increment [rad]
 *   void  integrator_get(void *, double rotation[3]);   the step's rotation vector [rad];
 *                                                       starts the next step
 *
 * The class is Savage's per-sample recursion (Savage 1998, part 1, section 7.1.2),
 * the shape of an autopilot's coning integrator: the accumulated angle alpha, the
 * coning term beta, and the previous sample's increment kept across steps:
 *
 *   beta  += 1/2 (alpha + dalpha_prev/6) x dalpha,   alpha += dalpha
 *
 * Build:  c++ -O2 -shared -fPIC -o libintegrator_cpp.so docs/integrator_example.cpp
 * Use:    per_sample_library("./libintegrator_cpp.so", "integrator_", handle=True)
 */
#include <array>

namespace {

using Vec = std::array<double, 3>;

Vec cross(const Vec &a, const Vec &b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

class ConingIntegrator {
public:
    void reset()
    {
        alpha_ = beta_ = last_ = Vec{0.0, 0.0, 0.0};
    }

    void put(const Vec &d)
    {
        Vec read{alpha_[0] + last_[0] / 6.0, alpha_[1] + last_[1] / 6.0, alpha_[2] + last_[2] / 6.0};
        Vec c = cross(read, d);
        for (int i = 0; i < 3; ++i) {
            beta_[i] += 0.5 * c[i];
            alpha_[i] += d[i];
        }
        last_ = d;
    }

    Vec get()
    {
        Vec out{alpha_[0] + beta_[0], alpha_[1] + beta_[1], alpha_[2] + beta_[2]};
        alpha_ = beta_ = Vec{0.0, 0.0, 0.0};  // the previous increment is kept across steps
        return out;
    }

private:
    Vec alpha_{}, beta_{}, last_{};
};

}  // namespace

extern "C" {

void *integrator_create(void) { return new ConingIntegrator(); }

void integrator_destroy(void *self) { delete static_cast<ConingIntegrator *>(self); }

void integrator_reset(void *self) { static_cast<ConingIntegrator *>(self)->reset(); }

void integrator_put(void *self, const double *gyro)
{
    static_cast<ConingIntegrator *>(self)->put(Vec{gyro[0], gyro[1], gyro[2]});
}

void integrator_get(void *self, double *rotation)
{
    Vec out = static_cast<ConingIntegrator *>(self)->get();
    for (int i = 0; i < 3; ++i)
        rotation[i] = out[i];
}

}  // extern "C"
