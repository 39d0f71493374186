/* Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0. */
/*
 * mjformation plugin ABI, version 4.
 *
 * Version 4 (this wave): a plugin declares its state (mjfPlugin.state_size, get_state,
 * set_state, appended at the end): every number that carries from one compute() to the next,
 * as a fixed count of doubles, so that a host can copy, checkpoint and rewind an instance
 * (MuJoCo's plugin_state, checkpoint and resume). A C++ plugin gets the three from one
 * VisitState member (plugin_state.hpp). An ABI-3 library is refused at load with a message
 * naming both versions and docs/PLUGINS.md, "Migrating from ABI 3". mjfSensorInfo also says
 * when aiding samples are taken (aiding_period, appended at the end).
 *
 * Version 3: the estimator kind (MJF_KIND_ESTIMATOR, mjfImuSample, mjfMeasurement,
 * mjfEstimatorInput, mjfEstimate, mjfSensorInfo; appended to mjfCreateContext and
 * mjfStepContext), and the vehicle info says which actuation contract the vehicle's actuators
 * follow (mjfVehicleInfo.actuation: four rotors, or one collective thrust and three body
 * moments). Every new member is at the end of its struct or enum.
 *
 * Version 2: compute() can say why it failed (mjfStepContext.error), and formation
 * protocols can run as one instance per follower over a simulated network
 * (MJF_KIND_FORMATION_AGENT, mjfNeighbourhood, mjfAgentInput, mjfMessage). A library built for
 * another version is refused at load with a message naming both versions.
 *
 * The ABI is mjformation's own, with the shape of MuJoCo's native engine plugins (mjpPlugin): a
 * descriptor with a name, a kind, declared attributes with defaults, and create / compute /
 * reset / destroy callbacks. It was written when the runner was on MuJoCo 2.2.2, which had no
 * engine plugins; it holds no MuJoCo type, so a plugin needs no MuJoCo headers to be built.
 *
 * A shared library exports one C function, MJF_ENTRY_SYMBOL, returning an array of descriptors
 * (a plugin family, e.g. all guidance laws, is one library). The host (runner/plugin_host.*)
 * finds libraries on a search path, dlopen()s them, refuses an ABI mismatch, checks attributes
 * against the declaration, and calls the callbacks from its own stepping loop
 * (mj_step1 / plugins / mj_step2). No plugin may keep global mutable state: several
 * simulations run in one process, each on its own thread.
 *
 * Units are SI. World frame is ENU-like: z up, gravity -z. Vehicle index 0 is the leader,
 * 1..N are the followers (the paper's numbering).
 */
#ifndef MJFORMATION_PLUGIN_H_
#define MJFORMATION_PLUGIN_H_

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bump on any change of the structs or callbacks below. */
#define MJF_ABI_VERSION 4u

/* Name of the exported entry point: const mjfPlugin* const* mjf_plugin_entry(int* count). */
#define MJF_ENTRY_SYMBOL "mjf_plugin_entry"

/* Marks the entry point exported whatever the build hides (-fvisibility=hidden, which
   mjformation_add_plugin and most CMake projects set): write
     MJF_PLUGIN_EXPORT const mjfPlugin* const* mjf_plugin_entry(int* count) { ... }
   in C (C++: MJF_EXPORT_PLUGINS of plugin_util.hpp does it). */
#if defined(_WIN32)
#define MJF_PLUGIN_EXPORT __declspec(dllexport)
#else
#define MJF_PLUGIN_EXPORT __attribute__((visibility("default")))
#endif

struct mjModel_;
struct mjData_;

typedef enum mjfKind_ {
  MJF_KIND_GUIDANCE = 1,  /* one instance per vehicle: own trajectory -> setpoint (leader, hover) */
  MJF_KIND_FORMATION = 2, /* one instance per swarm: neighbours' states -> follower setpoints */
  MJF_KIND_ATTITUDE = 3,  /* one instance per vehicle: setpoint -> actuator controls */
  MJF_KIND_FORMATION_AGENT = 4, /* one instance per follower: own state + received messages ->
                                   own setpoint (distributed execution, see mjfAgentInput) */
  MJF_KIND_ESTIMATOR = 5 /* ABI 3: one instance per vehicle: IMU + time-stamped measurements ->
                            the state estimate the controllers see (see mjfEstimatorInput) */
} mjfKind;

/* A declared attribute. Values reach create() as strings (like mjpPlugin attributes). */
typedef struct mjfAttribute_ {
  const char* key;           /* short lowercase key, e.g. "rho" */
  const char* default_value; /* NULL: the attribute is required */
  const char* doc;           /* one line: meaning and unit */
} mjfAttribute;

/* What the vehicle's sensors report (never qpos): see docs/VEHICLES.md for the sensor names. */
typedef struct mjfVehicleState_ {
  double pos[3];  /* m, world frame */
  double vel[3];  /* m/s, world frame */
  double quat[4]; /* w x y z, body -> world */
  double gyro[3]; /* rad/s, body frame */
} mjfVehicleState;

/* The typed per-vehicle setpoint bus. Guidance and formation plugins write it; attitude plugins
 * read it. The host clears the diagnostic fields to NaN before each formation tick. */
/* Before each formation tick the host fills every follower's pos[2] (altitude setpoint), vel[2],
 * acc[2] (0) and yaw (0) and sets sliding to NaN; formation plugins write only x and y. */
typedef struct mjfSetpoint_ {
  double acc[3];     /* desired acceleration, m/s^2, world frame (x, y horizontal command; z
                        feedforward) */
  double pos[3];     /* reference position, m (z: altitude setpoint) */
  double vel[3];     /* reference velocity, m/s */
  double yaw;        /* yaw setpoint, rad */
  double sliding[2]; /* diagnostic: sliding variable s_i for x and y (NaN when not applicable) */
} mjfSetpoint;

/* One actuator an attitude plugin drives, resolved by the host from the composed model. */
typedef struct mjfActuatorInfo_ {
  double site_pos[3]; /* m, actuator site relative to the vehicle's centre of mass, body-frame axes
                         (0 for joint actuators) */
  double gear[6];     /* actuator gear: force (0..2) and torque (3..5) per unit control */
  double ctrl_min;    /* ctrlrange (or -inf/inf when unlimited) */
  double ctrl_max;
  double time_constant; /* s, first-order actuator lag (dyntype filter), 0 when none */
} mjfActuatorInfo;

/* How the actuators an attitude plugin drives move the vehicle (mjfVehicleInfo.actuation). */
typedef enum mjfActuation_ {
  /* Rotors: each actuator is one rotor (force along its gear at its site, plus its reaction
   * torque); the plugin allocates the wrench over them (docs/VEHICLES.md). */
  MJF_ACTUATION_ROTORS = 0,
  /* Thrust and moments: actuator 0 is the collective thrust along body z, actuators 1..3 the
   * body moments about x, y, z ([vehicles] thrust, moments); each control is that wrench
   * component divided by its gear, within its ctrlrange. No mixing. */
  MJF_ACTUATION_THRUST_MOMENTS = 1
} mjfActuation;

/* What an attitude or guidance plugin knows of its vehicle. */
typedef struct mjfVehicleInfo_ {
  double mass;       /* kg, whole vehicle */
  double inertia[3]; /* kg m^2, principal moments of the vehicle's root body */
  double gravity;    /* m/s^2, magnitude */
  int n_actuators;   /* equals the plugin's n_actuators */
  const mjfActuatorInfo* actuators;
  int actuation; /* appended in version 3: an mjfActuation, what the actuators above are */
} mjfVehicleInfo;

/* Directed follower graph (paper section 2): follower indices 0..n-1 here (paper's i = index+1). */
typedef struct mjfGraph_ {
  int n_followers;
  const double* leader_weight; /* [n_followers] a_i0 */
  int n_edges;
  const int* edge_from;      /* j: follower i receives j's state (edge j -> i) */
  const int* edge_to;        /* i */
  const double* edge_weight; /* a_ij > 0 */
} mjfGraph;

/* Desired formation (Definition 1): offsets f_i(t) of each follower from the leader. */
typedef struct mjfShape_ {
  int n_followers;
  const void* self;
  /* Fills out[6*i + k] for follower i, k = (px, py, vx, vy, ax, ay) at time t. */
  void (*evaluate)(const void* self, double t, double* out);
  /* Appended at the end (still version 2, so older plugins keep their layout): fills out[0..5] for
   * one follower with what evaluate() writes at out[6*follower ..], bit for bit, at a cost
   * independent of n_followers, so a per-agent instance evaluates only itself and its neighbours
   * (per-agent cost linear in N). The host always sets it; a shape from elsewhere may leave it
   * NULL. */
  void (*evaluate_one)(const void* self, double t, int follower, double* out);
} mjfShape;

/* What one follower knows of the graph (per-agent formation plugins): its own row of L_H. */
typedef struct mjfNeighbourhood_ {
  int follower; /* this follower, 0..n_followers-1 (paper's i = follower + 1) */
  int n_followers;
  double leader_weight;  /* a_i0 (0: this follower does not hear the leader) */
  int n_neighbours;      /* in-neighbours j (edges j -> i) */
  const int* neighbours; /* [n_neighbours] follower indices j */
  const double* weights; /* [n_neighbours] a_ij > 0 */
} mjfNeighbourhood;

/* Generic payload slots a per-agent protocol may add to its broadcast (e.g. a Jacobi iterate). */
#define MJF_MESSAGE_PAYLOAD 8

/* One message as received over a simulated link (or the follower's own outgoing message). */
typedef struct mjfMessage_ {
  int sender;            /* vehicle index of the sender: 0 = leader, 1..N = followers */
  int round;             /* exchange round within the sample (0 .. n_rounds-1) */
  double send_time;      /* s, simulation time at which the sender broadcast it */
  mjfVehicleState state; /* the sender's state as it measured it */
  double input[3];       /* the sender's last formation input u_j (world frame); NaN: none */
  int n_payload;         /* used payload slots */
  double payload[MJF_MESSAGE_PAYLOAD];
} mjfMessage;

/* Handed to a per-agent formation plugin on each compute() (ctx->agent). The host never hands
 * such a plugin the swarm's arrays: ctx->states, ctx->model and ctx->data are NULL and
 * ctx->setpoints points at this follower's own setpoint only. */
typedef struct mjfAgentInput_ {
  int follower;                /* 0-based follower index (vehicle follower + 1) */
  const mjfVehicleState* self; /* this follower's own measured state */
  int n_messages;              /* the newest message held from each in-neighbour */
  const mjfMessage* messages;
  const mjfMessage* leader; /* newest leader message, NULL when a_i0 = 0 or none yet */
  int round;                /* exchange round of this call within the sample */
  int n_rounds;             /* rounds per sample (1 unless Jacobi exchange is configured) */
  mjfMessage* outgoing;     /* what this follower broadcasts next: the host fills sender,
                               time, state and input (from the setpoint written); the plugin
                               may fill round-specific payload */
  /* Added at the end (older plugins keep their layout): with [execution] coupling =
   * "central_solve", in the last round of a sample the host's exact solve of L_H W = R for this
   * follower (W_i for x and y, where R_i is what the plugin published in outgoing->payload[2..3] in
   * round 0; see docs/NETWORK.md); NULL otherwise. The ideal-network reference, not a distributed
   * scheme. */
  const double* solved;
} mjfAgentInput;

/* ABI 3, estimator plugins. What a measurement carries (bits of mjfMeasurement.fields). */
#define MJF_MEASURES_POSITION 1u
#define MJF_MEASURES_VELOCITY 2u
#define MJF_MEASURES_ATTITUDE 4u
#define MJF_MEASURES_BODY_RATE 8u

/* The inertial sample of one physics step (taken now, no latency). */
typedef struct mjfImuSample_ {
  double time;        /* s, when it was taken (= the step's time) */
  int has_accel;      /* 0: the vehicle has no accelerometer channel */
  int accel_in_world; /* 1: accel is in the world frame (point mass), 0: body frame */
  double accel[3];    /* specific force a - g, m/s^2 (at rest, level: +g up) */
  double quat[4];     /* attitude channel, w x y z, body -> world (rotates a body-frame accel) */
  double gyro[3];     /* rad/s, body frame */
} mjfImuSample;

/* One sample of an aiding sensor (GNSS, RTK, motion capture) that arrived in this step. */
typedef struct mjfMeasurement_ {
  double time_taken; /* s, when the sensor took it (arrival time minus its latency) */
  unsigned fields;   /* MJF_MEASURES_* bits: which of the members below are valid */
  double pos[3];     /* m, world frame */
  double vel[3];     /* m/s, world frame */
  double quat[4];    /* w x y z */
  double gyro[3];    /* rad/s, body frame */
  double pos_std[3]; /* m, 1 sigma per axis the suite states for pos (white + wander) */
  double vel_std[3]; /* m/s, 1 sigma per axis for vel */
} mjfMeasurement;

/* Handed to an estimator plugin on each compute() (ctx->estimator); it writes ctx->estimate. */
typedef struct mjfEstimatorInput_ {
  int vehicle;
  mjfImuSample imu;
  int n_measurements; /* the measurements that arrived in this step, oldest taken first */
  const mjfMeasurement* measurements;
  const mjfVehicleState* held; /* the sensor stage's held samples (what ABI 2 controllers saw) */
} mjfEstimatorInput;

/* What an estimator returns for the current time; the controllers see `state` only. */
typedef struct mjfEstimate_ {
  mjfVehicleState state;
  double covariance[36]; /* row-major 6x6 of (pos x y z, vel x y z), m^2, m^2/s, m^2/s^2; NaN:
                            the estimator does not know it */
  int64_t rejected;      /* measurements refused by the innovation gate so far */
  int64_t fused;         /* measurements fused so far */
} mjfEstimate;

/* What an estimator plugin knows of its vehicle's sensor suite (ctx->sensors at create()). */
typedef struct mjfSensorInfo_ {
  int has_accel;
  int accel_in_world;
  double accel_noise_density; /* m/s^2/sqrt(Hz), white specific-force noise */
  double accel_bias_walk;     /* m/s^3/sqrt(Hz), bias random-walk intensity */
  unsigned position_sources;  /* MJF_MEASURES_* bits provided by some aiding sensor */
  double max_latency;         /* s, the largest latency of any aiding sensor */
  /* The position source's first-order Gauss-Markov wander per axis (stationary 1 sigma and
     correlation time; 0: none). A measurement's pos_std is sqrt(white^2 + wander^2). */
  double position_wander_std; /* m */
  double position_wander_tau; /* s */
  /* s: every aiding sample (position, velocity) is taken at a whole multiple of it, counted from
     t = 0 (the channels' common sample period), so an estimator that keeps past estimates for
     late samples needs only those steps'; 0: at any step. */
  double aiding_period;
} mjfSensorInfo;

typedef struct mjfCreateContext_ {
  /* Attributes: every declared key, in declaration order, with defaults filled in. */
  int n_attributes;
  const char* const* keys;
  const char* const* values;
  double timestep; /* s, physics step */
  int vehicle;     /* per-vehicle plugins: the vehicle index; -1 for formation plugins */
  int n_vehicles;  /* 1 + number of followers */
  const mjfVehicleInfo* vehicle_info; /* per-vehicle plugins; NULL for formation plugins */
  const double* initial_pos;          /* [3] per-vehicle plugins: the vehicle's initial position */
  const mjfGraph* graph;              /* formation plugins; NULL otherwise */
  const mjfShape* shape;              /* formation plugins (both kinds); NULL otherwise */
  const mjfNeighbourhood* neighbourhood; /* per-agent formation plugins; NULL otherwise */
  const struct mjModel_* model;          /* raw access, may be NULL (unit tests) */
  char* error; /* create() writes a one-line reason here when it returns NULL */
  size_t error_size;
  const mjfSensorInfo* sensors; /* ABI 3: estimator plugins; NULL otherwise */
} mjfCreateContext;

typedef struct mjfStepContext_ {
  double time;  /* s, simulation time at this step (before it is taken) */
  int64_t step; /* physics step index: time = step * timestep exactly in intent */
  double timestep;
  int n_vehicles;
  const mjfVehicleState* states; /* [n_vehicles], 0 = leader */
  mjfSetpoint* setpoints;        /* [n_vehicles], the bus */
  double* controls; /* attitude plugins: [n_actuators] for this vehicle; NULL otherwise */
  const struct mjModel_* model; /* raw access, may be NULL */
  const struct mjData_* data;
  /* compute() may write a one-line reason here before it returns nonzero; the host reports it
   * with the plugin's name, the vehicle and the time. Always non-NULL when called by the host. */
  char* error;
  size_t error_size;
  const mjfAgentInput* agent; /* per-agent formation plugins; NULL otherwise */
  /* ABI 3, estimator plugins (NULL otherwise): this step's IMU sample and arrived
   * measurements, and where the estimate for ctx->time goes. ctx->states is NULL for them. */
  const mjfEstimatorInput* estimator;
  mjfEstimate* estimate;
} mjfStepContext;

/* Optional reporting of scalar results into summary.json (e.g. "delta", "error_bound"). */
typedef void (*mjfReportFn)(void* user, const char* key, double value);

typedef struct mjfPlugin_ {
  uint32_t abi_version; /* MJF_ABI_VERSION the plugin was compiled against */
  const char* name;     /* unique, lowercase: "smc_discrete" */
  mjfKind kind;
  const char* doc; /* one line */
  int n_attributes;
  const mjfAttribute* attributes;
  int n_actuators;              /* attitude plugins: actuators driven, per vehicle */
  const char* const* actuators; /* their names without the vehicle prefix, e.g. "rotor0" */
  void* (*create)(const mjfCreateContext* ctx);              /* NULL + ctx->error on bad config */
  int (*compute)(void* instance, const mjfStepContext* ctx); /* 0 ok; nonzero: stop the run
                                                                (ctx->error may say why) */
  void (*reset)(void* instance);
  void (*destroy)(void* instance);
  void (*report)(void* instance, mjfReportFn emit, void* user); /* may be NULL */
  /* Appended in version 4: the instance's state, everything compute() reads that an earlier
   * compute() wrote (held samples and their phase, integrators, filters, random streams).
   * state_size: the number of doubles, fixed from create() to destroy(). get_state writes them
   * to out[0 .. state_size - 1]; set_state reads them back, after which the instance computes
   * exactly (bit for bit) what the instance that wrote them would have. Integers and flags
   * are stored exactly as doubles. NULL state_size: the plugin has no state (get_state and
   * set_state are then not called). A host may call set_state before any compute(). */
  size_t (*state_size)(void* instance);
  void (*get_state)(void* instance, double* out);
  void (*set_state)(void* instance, const double* in);
} mjfPlugin;

typedef const mjfPlugin* const* (*mjfEntryFn)(int* count);

#ifdef __cplusplus
}
#endif

#endif /* MJFORMATION_PLUGIN_H_ */
