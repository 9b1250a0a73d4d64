/* The door between a compiled simulation plugin and the pfgen runtime: plain C, so that it
 * means the same to every compiler and to C and C++ alike.
 *
 * A plugin is a shared object built by `pfgen simulate` from one model: its truth
 * dx = f(x,t) dt + g(x,t) dW1, its observation dy = (A0(t) + A(t) x(t - h)) dt + B(t) dW2 (h = 0
 * but in version 3 on; or samples y_k = C0 + C x(t_k) + Uv v_k, version 2 on; or, version 4 on,
 * dy = h(x, t) dt + B(t) dW2 with a nonlinear rate h, or samples c(x(t_k)) + Uv v_k), and any
 * number of generated filters, all at the model's default parameter values. It exports one
 * function, PFGEN_PLUGIN_ENTRY_NAME, returning a table that lives as long as the plugin is loaded.
 *
 * This file is the one definition of the ABI: the runtime includes it, and pfgen embeds its text
 * at build time and pastes it into every plugin source it generates. Any change of layout or
 * meaning must raise PFGEN_PLUGIN_ABI_VERSION; abi_version stays the first member forever, so
 * that a loader can reject any other version before reading anything else.
 *
 * Arrays are row-major; every function is reentrant (no state), so threads may share a plugin.
 */
#ifndef PFGEN_PLUGIN_ABI_H
#define PFGEN_PLUGIN_ABI_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PFGEN_PLUGIN_ABI_VERSION 10u
#define PFGEN_PLUGIN_ENTRY_NAME "pfgen_plugin_entry"

/* One filter over its packed state [m (n entries), upper triangle of P row by row], followed by
 * extra_state_size entries of its own (a delayed filter's x* and the history of its last D grid
 * values; 0 for others) that only the filter reads. A filter with fixed_dt > 0 was generated for
 * the grid t_k = k fixed_dt and must be stepped once per grid step on exactly that grid
 * (step's t = t_k, dt = fixed_dt); fixed_dt = 0: any t and dt. */
typedef struct pfgen_plugin_filter {
  const char* name;
  size_t n, p;
  size_t state_size; /* n + n(n+1)/2: m and P */
  void (*initial_state)(double* state);                                 /* from the model's m0, P0 */
  void (*step)(double* state, double t, double dt, const double* dy);   /* over [t, t+dt], dy: p */
  size_t extra_state_size; /* entries after m and P (version 3 on) */
  double fixed_dt;         /* 0, or the only grid step the filter accepts (version 3 on) */
  /* Version 6 on: `lanes` filter states stepped at once over the same [t, t+dt], entry-major
   * (state[e * lanes + k] is entry e of state k, dy[r * lanes + k] entry r of its increment), so
   * that independent runs share SIMD registers and hide each other's latency. Lane k's result is
   * bit for bit step()'s on state k. NULL, and lanes 0, for a filter with extra state. */
  void (*step_lanes)(double* state, double t, double dt, const double* dy);
  size_t lanes;
  /* Version 7 on: step at parameter values given in the call (values: the plugin's
   * parameter_count entries, in the model's order) rather than the model's defaults, and the
   * predicted observation rate h (p entries: A0 + A m, or E[h(x)]) of the state at t. Both NULL,
   * or both set. What running a filter over recorded data and fitting parameters need. Version 8
   * on, a delayed filter has them too: state is then the whole flat state (with its extra state)
   * and t a time of its grid t_k = k fixed_dt, as for step; predicted_observation gives
   * A0 + A m(t - h), m(t - h) from the filter's history (what step's predictor reads). */
  void (*step_at)(double* state, const double* values, double t, double dt, const double* dy);
  void (*predicted_observation)(const double* state, const double* values, double t, double* h);
  /* Version 9 on: a moment filter (closure3, closure4) carries its central moments above P as extra
   * state on any grid (fixed_dt 0), and gives its realisability margins: margin_count values, each
   * positive while its moments can be a law's, named by margin_names; NULL and 0 for the others. */
  size_t margin_count;
  void (*realisability_margins)(const double* state, double* margins);
  const char* const* margin_names;
} pfgen_plugin_filter;

/* One filter for sampled observations (y_k = C0 + C x(t_k) + Uv v_k every `period`) over the
 * same packed state: `substeps` predictions of dt = period / substeps between samples, then one
 * update. update returns 0, leaving the state unchanged, when C P C^T + Uv Uv^T is not positive
 * definite. */
typedef struct pfgen_plugin_sampled_filter {
  const char* name;
  size_t n, p;
  size_t state_size; /* n + n(n+1)/2 */
  size_t substeps;   /* >= 1 */
  void (*initial_state)(double* state);
  void (*predict)(double* state, double t, double dt);  /* one sub-step over [t, t+dt] */
  int (*update)(double* state, double t, const double* y); /* the sample y (p entries) taken at t */
  /* Version 7 on: predict and update at parameter values given in the call (the plugin's
   * parameter_count entries, in the model's order), and the sample's predicted value yhat (p) with
   * its innovation covariance S = C P C^T + Uv Uv^T (p x p, row-major; for a polynomial c,
   * Cov(c) + Uv Uv^T) before an update at t. */
  void (*predict_at)(double* state, const double* values, double t, double dt);
  int (*update_at)(double* state, const double* values, double t, const double* y);
  void (*innovation)(const double* state, const double* values, double t, double* yhat, double* S);
  /* Version 10 on: a sampled moment filter (cd-closure3, cd-closure4) carries its central moments above P
   * as extra_state_size entries after m and P, and gives its realisability margins as a continuous moment
   * filter does (margin_count values, named by margin_names); 0 and NULL for the others. */
  size_t extra_state_size;
  size_t margin_count;
  void (*realisability_margins)(const double* state, double* margins);
  const char* const* margin_names;
} pfgen_plugin_sampled_filter;

typedef struct pfgen_plugin {
  unsigned abi_version; /* PFGEN_PLUGIN_ABI_VERSION of the generator that wrote the plugin */
  const char* model_name;
  const char* pfgen_version;
  size_t n; /* states */
  size_t q; /* truth Wiener processes: columns of g, or n when only G is given; 0 iff diffusion_is_zero */
  size_t p; /* observations */
  size_t r; /* observation Wiener processes: columns of B */
  int diffusion_is_zero;       /* g identically zero: a deterministic truth, no diffusion functions */
  int diffusion_is_covariance; /* the model gives only G = g g^T: diffusion_covariance is set,
                                  diffusion and diffusion_jacobian are NULL */
  int observation_is_constant; /* A0, A, B do not depend on t */
  /* The model's initial.x0 (n entries); NULL when the model gives none. */
  void (*truth_initial_state)(double* x0);
  void (*drift)(double t, const double* x, double* f);                /* f: n */
  void (*diffusion)(double t, const double* x, double* g);            /* g: n x q, or NULL */
  /* dg[(i*q + j)*n + l] = d g_ij / d x_l, or NULL */
  void (*diffusion_jacobian)(double t, const double* x, double* dg);
  void (*diffusion_covariance)(double t, const double* x, double* G); /* G: n x n, or NULL */
  void (*observation)(double t, double* A0, double* A, double* B);    /* A0: p, A: p x n, B: p x r */
  size_t filter_count;
  const pfgen_plugin_filter* filters; /* filter_count entries (NULL when 0) */
  /* Sampled observations (observation_is_sampled = 1): observation and filters are NULL and
   * filter_count 0; p is the rows of C, r the columns of Uv, and sampled_observation fills
   * C0 (p), C (p x n) and Uv (p x r) at a sample time. Continuous ones: all of these 0 or NULL. */
  int observation_is_sampled;
  double period; /* T > 0: samples at t_k = k T, k >= 1 */
  void (*sampled_observation)(double t, double* C0, double* C, double* Uv);
  size_t sampled_filter_count;
  const pfgen_plugin_sampled_filter* sampled_filters; /* sampled_filter_count entries (NULL when 0) */
  /* Continuous observations with a delay (version 3 on): dy reads the truth at t - h, with
   * x(s) = x(0) for s < 0. delay_steps = h / delay_dt, the grid step the plugin's filters were
   * generated for; all three 0 without a delay. */
  double delay;
  double delay_dt;
  size_t delay_steps;
  /* A nonlinear observation function (version 4 on), p entries: for continuous observations the
   * rate h of dy = h(x, t) dt + B(t) dW2, in place of A0 + A x (observation still gives B, its A0
   * and A zero); for sampled ones the c of y_k = c(x(t_k)) + Uv v_k, in place of C0 + C x
   * (sampled_observation still gives Uv, its C0 and C zero). NULL for a linear observation and
   * with a delay. */
  void (*observation_rate)(double t, const double* x, double* h);
  /* Batched forms (version 5 on) of drift, diffusion and observation_rate, each NULL exactly when
   * its one-state form is: `count` states at one t, entry-major (structure of arrays), so that
   * x[i * count + k] is entry i of state k and likewise out[e * count + k] entry e of its result
   * (g's entry e = i * q + j). Lane k's result is bit for bit the one-state function's on state
   * k: many particles cost one call, and the lanes' arithmetic can share SIMD registers. */
  void (*drift_batch)(double t, size_t count, const double* x, double* f);
  void (*diffusion_batch)(double t, size_t count, const double* x, double* g);
  void (*observation_rate_batch)(double t, size_t count, const double* x, double* h);
  /* Version 7 on: the model's parameters in its order (names and the default values every
   * function above uses), and for continuous observations (version 8 on: with a delay too) B(t)
   * (p x r) at given parameter values: the observation noise dW2's factor, R = B B^T (NULL
   * otherwise, or from a plugin whose continuous filters cannot run on records). */
  size_t parameter_count;
  const char* const* parameter_names;  /* parameter_count entries (NULL when 0) */
  const double* parameter_defaults;    /* parameter_count entries (NULL when 0) */
  void (*observation_noise)(const double* values, double t, double* B);
} pfgen_plugin;

/* The exported entry point: const pfgen_plugin* pfgen_plugin_entry(void). */
typedef const pfgen_plugin* (*pfgen_plugin_entry_function)(void);

#ifdef __cplusplus
}
#endif

#endif /* PFGEN_PLUGIN_ABI_H */
