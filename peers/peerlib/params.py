# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""One Crazyflie-class reference vehicle and its translation into each simulator's parameters.

The reference numbers are RotorPy 3.0's `crazyflie_params` (mass, inertia, 0.043 m arm at 45
degrees, k_eta, k_m, 2500 rad/s top speed, motor time constant), because they are the most
completely documented set among the peers (Forster 2015; Eschmann et al. 2024). What is matched:
mass, inertia, rotor positions and spin, thrust and torque coefficients, top thrust and the
motor time constant (Izz excepted: see REFERENCE). What each peer keeps of its own (drag, propeller inertia, integrator) is
listed by `unmatched()` and discussed in docs/PEERS.md.

Rotor order everywhere here is the reference's: r1 (+x,+y), r2 (+x,-y), r3 (-x,-y), r4 (-x,+y),
yaw sign +1, -1, +1, -1 (the body torque about +z per unit thrust is sign * k_m / k_eta)."""

import math
import xml.sax.saxutils as _sax

G = 9.81  # m/s^2, every peer's gravity

REFERENCE = {
    "mass": 0.030,            # kg
    "ixx": 1.43e-5,           # kg m^2
    "iyy": 1.43e-5,
    "izz": 2.85e-5,           # RotorPy's 2.89e-5 breaks Ixx + Iyy >= Izz, which Bullet and
                              # MuJoCo require of a rigid body: taken 0.35 % under Ixx + Iyy
    "arm": 0.043,             # m, centre of mass to rotor hub
    "k_eta": 2.3e-8,          # N / (rad/s)^2, thrust = k_eta w^2
    "k_m": 7.8e-10,           # N m / (rad/s)^2, yaw reaction = k_m w^2
    "omega_max": 2500.0,      # rad/s
    "tau_m": 0.072,           # s, first-order motor time constant
}
SIGNS = (1, -1, 1, -1)       # yaw reaction sign of r1..r4
QUADRANTS = ((1, 1), (1, -1), (-1, -1), (-1, 1))  # (sign x, sign y) of r1..r4


def derived(ref=REFERENCE):
    """Quantities every conversion uses: per-axis offset, top thrust per rotor, yaw moment arm."""
    d = ref["arm"] / math.sqrt(2.0)
    t_max = ref["k_eta"] * ref["omega_max"] ** 2
    return {
        "offset": d,                                 # m, |x| = |y| of each hub
        "thrust_max": t_max,                         # N per rotor
        "yaw_arm": ref["k_m"] / ref["k_eta"],        # m, yaw torque per newton of thrust
        "hover_thrust": ref["mass"] * G / 4.0,       # N per rotor
        "hover_omega": math.sqrt(ref["mass"] * G / 4.0 / ref["k_eta"]),  # rad/s
        "thrust_to_weight": 4.0 * t_max / (ref["mass"] * G),
    }


def rotor_positions(ref=REFERENCE):
    d = derived(ref)["offset"]
    return [(sx * d, sy * d, 0.0) for sx, sy in QUADRANTS]


def allocation(positions, yaw_signs, yaw_arm):
    """4x4 map from per-rotor thrust (N) to [total thrust, tau_x, tau_y, tau_z] in the body frame
    (tau = r x (0, 0, T) = (y T, -x T, 0) plus the yaw reaction sign * yaw_arm * T)."""
    return [
        [1.0] * 4,
        [p[1] for p in positions],
        [-p[0] for p in positions],
        [s * yaw_arm for s in yaw_signs],
    ]


def match_order(peer_positions, peer_yaw_signs, ref=REFERENCE, tol=1e-9):
    """For each reference rotor r1..r4, the index of the peer's rotor at the same place with the
    same spin. Raises ValueError naming the rotor when a peer's layout cannot be matched (other
    quadrants, or the mirrored spin pattern, which would flip the sign of every yaw torque)."""
    order = []
    for i, ((sx, sy), sign) in enumerate(zip(QUADRANTS, SIGNS)):
        found = [j for j, (p, s) in enumerate(zip(peer_positions, peer_yaw_signs))
                 if p[0] * sx > tol and p[1] * sy > tol and s == sign]
        if len(found) != 1:
            raise ValueError(f"reference rotor r{i + 1} (quadrant {sx:+d}x {sy:+d}y, yaw sign "
                             f"{sign:+d}) matches {len(found)} rotors of the peer")
        order.append(found[0])
    return order


# ---- mjformation: an MJCF vehicle in the contract of docs/ARCHITECTURE.md ----------------------
MJCF_BODY = "cfref"
MJCF_ROTORS = ("r1", "r2", "r3", "r4")


def mjcf(ref=REFERENCE):
    """The reference vehicle as an MJCF with four thrust actuators (N, gain 1) behind a first-order
    filter of time constant tau_m (MuJoCo's dyntype filter), the yaw reaction in gear[5]."""
    d = derived(ref)
    sites, acts = [], []
    for name, (x, y, z), s in zip(MJCF_ROTORS, rotor_positions(ref), SIGNS):
        sites.append(f'      <site name="{name}" pos="{x:.9g} {y:.9g} {z:.9g}" size="0.003"/>')
        acts.append(f'    <general name="{name}" site="{name}" gear="0 0 1 0 0 {s * d["yaw_arm"]:.9g}" '
                    f'ctrlrange="0 {d["thrust_max"]:.9g}" ctrllimited="true" dyntype="filter" '
                    f'dynprm="{ref["tau_m"]:.9g}" gaintype="fixed" gainprm="1" biastype="none"/>')
    header = _sax.escape("peers harness reference vehicle (peers/peerlib/params.py)")
    return "\n".join([
        f"<!-- Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0."
        f"\n     {header}: generated, do not edit. -->",
        '<mujoco model="cfref">',
        '  <compiler inertiafromgeom="false" autolimits="true"/>',
        '  <option timestep="0.001" integrator="Euler" gravity="0 0 -9.81"/>',
        "  <worldbody>",
        f'    <body name="{MJCF_BODY}" pos="0 0 0.1">',
        "      <freejoint/>",
        f'      <inertial pos="0 0 0" mass="{ref["mass"]:.9g}" diaginertia="{ref["ixx"]:.9g} '
        f'{ref["iyy"]:.9g} {ref["izz"]:.9g}"/>',
        '      <geom name="hull" type="box" size="0.02 0.02 0.006" contype="0" conaffinity="0" group="2"/>',
        # bumper: touches the ground (contype 1), never another vehicle (as mjcf/quadrotor.xml)
        '      <geom name="bumper" type="box" size="0.04 0.04 0.008" group="3" contype="2" conaffinity="1"/>',
        '      <site name="imu" pos="0 0 0" size="0.002"/>',
        *sites,
        "    </body>",
        "  </worldbody>",
        "  <actuator>",
        *acts,
        "  </actuator>",
        "  <sensor>",
        '    <framepos name="pos" objtype="site" objname="imu"/>',
        '    <framelinvel name="vel" objtype="site" objname="imu"/>',
        '    <framequat name="quat" objtype="site" objname="imu"/>',
        '    <gyro name="gyro" site="imu"/>',
        "  </sensor>",
        "</mujoco>",
        "",
    ])


# ---- RotorPy ------------------------------------------------------------------------------------
def rotorpy_params(ref=REFERENCE, base=None):
    """RotorPy's quad_params dict: its own crazyflie_params (`base`) with the matched entries set.
    RotorPy's order r1..r4 and rotor_directions are the reference's by construction."""
    params = dict(base or {})
    d = derived(ref)
    params.update({
        "mass": ref["mass"], "Ixx": ref["ixx"], "Iyy": ref["iyy"], "Izz": ref["izz"],
        "Ixy": 0.0, "Iyz": 0.0, "Ixz": 0.0, "num_rotors": 4,
        "rotor_pos": {f"r{i + 1}": list(p) for i, p in enumerate(rotor_positions(ref))},
        "rotor_directions": list(SIGNS),
        "k_eta": ref["k_eta"], "k_m": ref["k_m"], "tau_m": ref["tau_m"],
        "rotor_speed_min": 0.0, "rotor_speed_max": ref["omega_max"], "motor_noise_std": 0.0,
    })
    assert abs(params["k_eta"] * params["rotor_speed_max"] ** 2 - d["thrust_max"]) < 1e-12
    return params


# ---- PyFlyt -------------------------------------------------------------------------------------
# PyFlyt's QuadX: motors 0..3 are URDF links prop1..prop4; torque_coef signs -, -, +, + (QuadX).
PYFLYT_YAW_SIGNS = (-1, -1, 1, 1)
PYFLYT_QUADRANTS = ((1, -1), (-1, 1), (1, 1), (-1, -1))


def pyflyt_positions(ref=REFERENCE):
    d = derived(ref)["offset"]
    return [(sx * d, sy * d, 0.0) for sx, sy in PYFLYT_QUADRANTS]


def pyflyt_order(ref=REFERENCE):
    """Reference rotor i is PyFlyt motor order[i]."""
    return match_order(pyflyt_positions(ref), PYFLYT_YAW_SIGNS, ref)


def pyflyt_yaml(ref=REFERENCE, drag=None, controller_yaml=""):
    """PyFlyt's motor_params with the matched values: thrust = thrust_coef (throttle max_rpm)^2,
    max_rpm = sqrt(total_thrust / (4 thrust_coef)), so thrust_coef = k_eta in rad/s units gives
    max_rpm = omega_max; noise off. drag: PyFlyt's own drag_params (kept, see unmatched())."""
    d = derived(ref)
    drag = drag or {"drag_coef_xyz": 3.0, "drag_area_xyz": 4.0e-4, "drag_coef_pqr": 1.0e-4}
    lines = ["motor_params:",
             f"  total_thrust: {4 * d['thrust_max']!r}",
             f"  thrust_coef: {ref['k_eta']!r}",
             f"  torque_coef: {ref['k_m']!r}",
             "  noise_ratio: 0.0",
             f"  tau: {ref['tau_m']!r}",
             "", "drag_params:"]
    lines += [f"  {k}: {v!r}" for k, v in drag.items()]
    return "\n".join(lines) + "\n\n" + controller_yaml


def pyflyt_urdf(ref=REFERENCE):
    """PyFlyt's cf2x.urdf structure (base_link, prop1..4, centre of mass, body) at the reference's
    mass, inertia and rotor positions; no visual mesh (nothing is rendered)."""
    def link(name, xyz=(0.0, 0.0, 0.0), mass=0.0, inertia=(0.0, 0.0, 0.0), extra=""):
        return (f'  <link name="{name}">\n    <inertial>\n      <origin rpy="0 0 0" xyz="{xyz[0]!r} '
                f'{xyz[1]!r} {xyz[2]!r}"/>\n      <mass value="{mass!r}"/>\n      <inertia ixx="{inertia[0]!r}"'
                f' ixy="0" ixz="0" iyy="{inertia[1]!r}" iyz="0" izz="{inertia[2]!r}"/>\n    </inertial>\n'
                f'{extra}  </link>\n')

    def joint(child):
        return (f'  <joint name="{child}_joint" type="fixed">\n    <parent link="base_link"/>\n'
                f'    <child link="{child}"/>\n  </joint>\n')
    collision = ('    <collision>\n      <origin rpy="0 0 0" xyz="0 0 0"/>\n      <geometry>\n'
                 '        <box size="0.09 0.09 0.02"/>\n      </geometry>\n    </collision>\n')
    out = ['<?xml version="1.0" ?>\n<!-- peers harness reference vehicle (peers/peerlib/params.py) -->\n'
           '<robot name="cfref">\n',
           link("base_link", mass=ref["mass"], inertia=(ref["ixx"], ref["iyy"], ref["izz"]), extra=collision)]
    for i, p in enumerate(pyflyt_positions(ref)):
        out += [link(f"prop{i + 1}_link", xyz=p), joint(f"prop{i + 1}_link")]
    out += [link("center_of_mass_link"), joint("center_of_mass_link"), link("body"), joint("body")]
    out.append("</robot>\n")
    return "".join(out)


def pyflyt_pwm(thrusts_ref, ref=REFERENCE):
    """Reference-order thrusts (N) -> PyFlyt motor pwm in its own order, through PyFlyt's thrust
    map thrust = (total_thrust / 4) pwm^2 at steady state."""
    t_max = derived(ref)["thrust_max"]
    pwm = [0.0] * 4
    for i, j in enumerate(pyflyt_order(ref)):
        pwm[j] = math.sqrt(max(thrusts_ref[i], 0.0) / t_max)
    return pwm


# ---- Crazyflow / drone-models first_principles -------------------------------------------------
# Its mixing matrix rows are (roll, pitch, yaw) signs per motor; torque_x = L * row0 . F etc.
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)


def crazyflow_mixing(ref=REFERENCE):
    """(3, 4) mixing matrix in Crazyflow's motor order (its cf2x: motor 0 at (+x,-y), 1 (-x,-y),
    2 (-x,+y), 3 (+x,+y)), from the reference layout: row0 = sign y, row1 = -sign x, row2 = yaw."""
    quads = ((1, -1), (-1, -1), (-1, 1), (1, 1))
    signs = []
    for q in quads:
        signs.append(SIGNS[QUADRANTS.index(q)])
    return [[float(q[1]) for q in quads], [float(-q[0]) for q in quads], [float(s) for s in signs]]


def crazyflow_order(ref=REFERENCE):
    quads = ((1, -1), (-1, -1), (-1, 1), (1, 1))
    d = derived(ref)["offset"]
    m = crazyflow_mixing(ref)
    return match_order([(q[0] * d, q[1] * d, 0.0) for q in quads], [int(s) for s in m[2]], ref)


def crazyflow_params(ref=REFERENCE):
    """Entries of crazyflow's first_principles Params set to the reference (rpm units: thrust =
    rpm2thrust[2] rpm^2 with rpm = w 60 / 2 pi); drag_matrix and prop_inertia stay its own."""
    k_rpm = (1.0 / RPM_PER_RAD_S) ** 2
    return {
        "mass": [ref["mass"]],
        "J": [[ref["ixx"], 0.0, 0.0], [0.0, ref["iyy"], 0.0], [0.0, 0.0, ref["izz"]]],
        "L": [derived(ref)["offset"]],
        "rpm2thrust": [[0.0, 0.0, ref["k_eta"] * k_rpm]],
        "rpm2torque": [[0.0, 0.0, ref["k_m"] * k_rpm]],
        "rotor_dyn_coef": [[1.0 / ref["tau_m"], 0.0, 1.0 / ref["tau_m"], 0.0]],
        "mixing_matrix": crazyflow_mixing(ref),
    }


def thrust_to_rpm(thrust):
    return math.sqrt(max(thrust, 0.0) / REFERENCE["k_eta"]) * RPM_PER_RAD_S


def thrust_to_omega(thrust, ref=REFERENCE):
    return math.sqrt(max(thrust, 0.0) / ref["k_eta"])


def unmatched():
    """What each model keeps of its own after matching (the cross-check explains these)."""
    return {
        "mjformation": "no aerodynamic drag, no propeller inertia; lag on thrust (MuJoCo filter); "
                       "semi-implicit Euler at 1 kHz",
        "rotorpy": "rotor drag H = -w K v_local (k_d 1.03e-6, k_z 7.55e-7 kg/rad, aero=True); "
                   "lag on rotor speed; RK45 (scipy solve_ivp) per step",
        "pyflyt": "body drag 0.5 rho Cd A v^2 (Cd 3, A 4e-4 m^2), rotational drag 1e-4 w^2; lag on "
                  "throttle (rpm fraction), explicit Euler in the motor; Bullet's integrator at 240 Hz",
        "crazyflow": "linear drag (cf2x_L250 drag_matrix -0.0150/-0.0150/-0.0139 N s/m); propeller "
                     "inertia 34.52e-9 kg m^2 (gyroscopic and reaction torques); lag on rpm; Euler",
    }
