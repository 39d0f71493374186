/* Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
 *
 * example_consensus_c: a formation law (one instance for the swarm) in plain C, against the
 * installed header alone (docs/PLUGINS.md, "A formation law"). It flies the standard
 * consensus-based formation tracking law
 *   u_i = f_ia - kp e_ip - kv e_iv,
 * where e_i is the local error of the paper's eq. (16), per horizontal axis:
 *   e_i = sum_j a_ij ((x_i - f_i) - (x_j - f_j)) + a_i0 (x_i - f_i - x_0).
 * The leader's acceleration is not used (the law lags a manoeuvring leader). What it shows:
 * where a law reads and writes, the 0-based follower numbers of the graph, and which pointers of
 * the host it may keep. */
#include <math.h>
#include <mjformation/plugin.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct {
  double kp, kv;
  /* The host's graph and shape: valid and unchanged from create() until destroy(), so they are
   * kept, never copied or freed. */
  const mjfGraph* graph;
  const mjfShape* shape;
  /* Work arrays, allocated once in create(): compute() allocates nothing. */
  double* f;     /* [6 N] the shape at this step: px py vx vy ax ay per follower */
  double* error; /* [4 N] e_ip x, y and e_iv x, y per follower */
} Law;

static const mjfAttribute kAttributes[] = {{"kp", "1", "1/s^2: position gain, > 0"},
                                           {"kv", "2", "1/s: velocity gain, > 0"}};

/* Attribute k as a number > 0. The key and value strings live only during create(). */
static int ReadGain(const mjfCreateContext* ctx, int k, double* out) {
  char* end = NULL;
  *out = strtod(ctx->values[k], &end);
  if (end == ctx->values[k] || *end != '\0' || !isfinite(*out) || !(*out > 0)) {
    snprintf(ctx->error, ctx->error_size, "%s = '%s': expected a number > 0", ctx->keys[k],
             ctx->values[k]);
    return 0;
  }
  return 1;
}

static void Destroy(void* instance) {
  Law* law = instance;
  if (law == NULL) return;
  free(law->f);
  free(law->error);
  free(law);
}

static void* Create(const mjfCreateContext* ctx) {
  if (ctx->graph == NULL || ctx->shape == NULL || ctx->n_vehicles != 1 + ctx->graph->n_followers) {
    snprintf(ctx->error, ctx->error_size, "needs the swarm's graph and shape (a formation law)");
    return NULL;
  }
  Law* law = calloc(1, sizeof(Law));
  if (law == NULL) return NULL;
  const int n = ctx->graph->n_followers;
  law->graph = ctx->graph;
  law->shape = ctx->shape;
  law->f = malloc(sizeof(double) * 6 * (size_t)n);
  law->error = malloc(sizeof(double) * 4 * (size_t)n);
  /* Attributes arrive in declaration order, defaults filled in: values[0] = kp, values[1] = kv. */
  if (law->f == NULL || law->error == NULL || !ReadGain(ctx, 0, &law->kp) ||
      !ReadGain(ctx, 1, &law->kv)) {
    Destroy(law);
    return NULL;
  }
  return law;
}

/* e_i of eq. (16): the leader's term, then one term per edge j -> i. The graph's follower
 * numbers are 0-based (follower i is vehicle i + 1); the experiment file's are 1-based. */
static void LocalErrors(const Law* law, const mjfStepContext* ctx) {
  const mjfGraph* g = law->graph;
  const mjfVehicleState* leader = &ctx->states[0];
  for (int i = 0; i < g->n_followers; ++i) {
    const mjfVehicleState* s = &ctx->states[i + 1];
    for (int a = 0; a < 2; ++a) {
      law->error[4 * i + a] =
          g->leader_weight[i] * (s->pos[a] - law->f[6 * i + a] - leader->pos[a]);
      law->error[4 * i + 2 + a] =
          g->leader_weight[i] * (s->vel[a] - law->f[6 * i + 2 + a] - leader->vel[a]);
    }
  }
  for (int k = 0; k < g->n_edges; ++k) {
    const int i = g->edge_to[k], j = g->edge_from[k];
    const mjfVehicleState* si = &ctx->states[i + 1];
    const mjfVehicleState* sj = &ctx->states[j + 1];
    for (int a = 0; a < 2; ++a) {
      law->error[4 * i + a] +=
          g->edge_weight[k] * ((si->pos[a] - law->f[6 * i + a]) - (sj->pos[a] - law->f[6 * j + a]));
      law->error[4 * i + 2 + a] += g->edge_weight[k] * ((si->vel[a] - law->f[6 * i + 2 + a]) -
                                                        (sj->vel[a] - law->f[6 * j + 2 + a]));
    }
  }
}

/* Writes, for follower i, only x and y of its setpoint (vehicle i + 1): acc = u_i, and its slot
 * pos = p_0 + f_ip, vel = v_0 + f_iv. The host has filled z, yaw and sliding (NaN) before. */
static int Compute(void* instance, const mjfStepContext* ctx) {
  Law* law = instance;
  const mjfVehicleState* leader = &ctx->states[0];
  law->shape->evaluate(law->shape->self, ctx->time, law->f);
  LocalErrors(law, ctx);
  for (int i = 0; i < law->graph->n_followers; ++i) {
    mjfSetpoint* sp = &ctx->setpoints[i + 1];
    for (int a = 0; a < 2; ++a) {
      const double u = law->f[6 * i + 4 + a] - law->kp * law->error[4 * i + a] -
                       law->kv * law->error[4 * i + 2 + a];
      if (!isfinite(u)) {
        snprintf(ctx->error, ctx->error_size, "follower %d: non-finite input (state or shape)",
                 i + 1);
        return 1;
      }
      sp->acc[a] = u;
      sp->pos[a] = leader->pos[a] + law->f[6 * i + a];
      sp->vel[a] = leader->vel[a] + law->f[6 * i + 2 + a];
    }
  }
  return 0;
}

static const mjfPlugin kConsensus = {MJF_ABI_VERSION,
                                     "example_consensus_c",
                                     MJF_KIND_FORMATION,
                                     "consensus formation tracking, in plain C (an example)",
                                     2,
                                     kAttributes,
                                     0,
                                     NULL,
                                     Create,
                                     Compute,
                                     NULL, /* reset: nothing is remembered between steps */
                                     Destroy,
                                     NULL,
                                     NULL, /* state_size (ABI 4): no state */
                                     NULL,
                                     NULL};
static const mjfPlugin* const kPlugins[] = {&kConsensus};

MJF_PLUGIN_EXPORT const mjfPlugin* const* mjf_plugin_entry(int* count) {
  *count = 1;
  return kPlugins;
}
