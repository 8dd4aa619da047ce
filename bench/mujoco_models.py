"""Gymnasium's MuJoCo models in rebond and in MuJoCo, side by side in the same run. Not a test;
see BENCHMARKS.md.

    pip install ./crates/rebond-py mujoco "gymnasium>=1.0,<2"
    python bench/mujoco_models.py [--seconds 5]

Each model of ``rebond/<Task>-v0`` (Gymnasium's own MJCF file) starts in the file's pose with
every control at zero and runs for ``--seconds`` of simulated time at the file's timestep in
both engines. rebond's controls are set (to zero) before every step, as the tasks do, which
keeps the model awake as MuJoCo's always is. Columns:

  height        the watched body's centre of mass height (MuJoCo's z, rebond's y) at the end, m
  speed         the speed of that centre of mass at the end, m/s
  limit excess  the worst excess of any limited hinge or slide beyond its range over the run
                after its first second (rad or m; Ant's file starts its ankles at 0, outside
                their 30° to 70° range, which both engines first push back into; MuJoCo's
                limits are soft, so it shows some excess too)
  steps/s       simulated steps per second of wall time, one world stepped from Python with
                its joint coordinates read every step (not a speed benchmark: see
                bench/python_batch.py)

The watched body is the torso (the pole for InvertedPendulum, the second pole for
InvertedDoublePendulum, the fingertip for Reacher). A last table gives InvertedPendulum's pole
period for a 0.05 rad swing with gravity turned upwards (so the upright pole swings) and the cart
held (its mass made a million times larger in both engines), against the period of the
rigid pendulum from MuJoCo's compiled mass, inertia, armature and joint damping ``c``:
``2π / √(m g d / I − (c / 2I)²)``.

It prints markdown tables and writes them as a CSV in bench/results/.
"""

from __future__ import annotations

import argparse
import csv
import datetime
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from python_batch import cpu_name  # noqa: E402

WATCHED = {
    "HalfCheetah": "torso",
    "Hopper": "torso",
    "Walker2d": "torso",
    "Ant": "torso",
    "Humanoid": "torso",
    "InvertedPendulum": "pole",
    "InvertedDoublePendulum": "pole2",
    "Reacher": "fingertip",
}
# rebond's Y-up frame back to the files' Z-up frame: (x, y, z) -> (x, -z, y).
TO_MJCF = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])


def limited_joints(model) -> list[tuple[str, float, float, int]]:
    """(name, lo, hi, qpos address) of MuJoCo's limited hinges and slides."""
    import mujoco

    joints = []
    for index in range(model.njnt):
        kind = model.jnt_type[index]
        if model.jnt_limited[index] and kind in (int(mujoco.mjtJoint.mjJNT_HINGE),
                                                 int(mujoco.mjtJoint.mjJNT_SLIDE)):
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, index)
            low, high = model.jnt_range[index]
            joints.append((name, float(low), float(high), int(model.jnt_qposadr[index])))
    return joints


def excess(values: np.ndarray, low: float, high: float) -> float:
    return float(max(0.0, np.max(values - high), np.max(low - values)))


def run_model(task: str, seconds: float) -> dict[str, float]:
    """Both engines on one model for ``seconds`` with zero controls."""
    import mujoco

    import rebond
    from rebond.mujoco_tasks import TASKS, assets_folder

    path = os.path.join(assets_folder(), TASKS[task]["xml"])
    model = mujoco.MjModel.from_xml_path(path)
    data = mujoco.MjData(model)
    world = rebond.World.from_scene(path)
    body = WATCHED[task]
    joints = limited_joints(model)
    names = world.joint_names()
    columns = [names.index(name) for name, _, _, _ in joints]
    # rebond's joint coordinates read MuJoCo's qpos0 (the joint's ref) in the file's pose.
    offsets = np.array([model.qpos0[address] for *_, address in joints])
    offsets = offsets - world.joint_positions()[columns].astype(np.float64)

    steps = int(round(seconds / model.opt.timestep))
    mujoco_q = np.empty((steps, len(joints)))
    start = time.perf_counter()
    for step in range(steps):
        mujoco.mj_step(model, data)
        mujoco_q[step] = [data.qpos[address] for *_, address in joints]
    mujoco_rate = steps / (time.perf_counter() - start)
    velocity = np.zeros(6)
    body_id = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, body)
    mujoco.mj_objectVelocity(model, data, mujoco.mjtObj.mjOBJ_BODY, body_id, velocity, 0)

    rebond_steps = int(round(seconds / world.timestep))
    rebond_q = np.empty((rebond_steps, len(joints)))
    zeros = np.zeros(len(world.actuator_names()))
    start = time.perf_counter()
    for step in range(rebond_steps):
        world.set_controls(zeros)
        world.step(1)
        rebond_q[step] = world.joint_positions()[columns] + offsets
    rebond_rate = rebond_steps / (time.perf_counter() - start)
    index = world.body_names().index(body)
    center = TO_MJCF @ world.centers_of_mass()[index].astype(np.float64)
    speed = np.linalg.norm(world.linear_velocities()[index].astype(np.float64))

    def worst(values: np.ndarray, timestep: float) -> float:
        """The worst excess after the first second."""
        values = values[int(round(1.0 / timestep)):]
        if not joints or len(values) == 0:
            return 0.0
        return max(excess(values[:, k], low, high) for k, (_, low, high, _) in enumerate(joints))

    return {
        "timestep": model.opt.timestep,
        "rebond_timestep": world.timestep,
        "rebond_height": float(center[2]),
        "mujoco_height": float(data.xipos[body_id][2]),
        "rebond_speed": float(speed),
        "mujoco_speed": float(np.linalg.norm(velocity[3:])),
        "rebond_excess": worst(rebond_q, world.timestep),
        "mujoco_excess": worst(mujoco_q, model.opt.timestep),
        "rebond_steps_per_s": rebond_rate,
        "mujoco_steps_per_s": mujoco_rate,
        "finite": bool(np.all(np.isfinite(rebond_q))),
    }


def swing_period(angles: np.ndarray, dt: float) -> float:
    """The mean period of a swing that settles: the spacing of its upward crossings of the
    angle it settles at (its last value; the pole's centre of mass is 0.5 mm off the hinge
    line, so that is not 0), over the first half of the run, interpolated linearly."""
    level = angles[-1]
    crossings = []
    for step in range(1, len(angles) // 2):
        before, after = angles[step - 1] - level, angles[step] - level
        if before < 0 <= after:
            crossings.append((step - 1 + before / (before - after)) * dt)
    if len(crossings) < 2:
        return float("nan")
    return float(np.mean(np.diff(crossings)))


def pendulum_periods(seconds: float, amplitude: float = 0.05) -> dict[str, float]:
    """InvertedPendulum's pole period with gravity upwards and the cart held, in both engines,
    and the rigid pendulum's from MuJoCo's compiled model."""
    import mujoco

    import rebond
    from rebond.mujoco_tasks import TASKS, assets_folder

    path = os.path.join(assets_folder(), TASKS["InvertedPendulum"]["xml"])
    model = mujoco.MjModel.from_xml_path(path)
    cart = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "cart")
    pole = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "pole")
    hinge = model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "hinge")]
    model.body_mass[cart] *= 1e6
    model.body_inertia[cart] *= 1e6
    model.opt.gravity[:] = -model.opt.gravity
    data = mujoco.MjData(model)
    data.qpos[hinge] = amplitude
    steps = int(round(seconds / model.opt.timestep))
    angles = np.empty(steps)
    for step in range(steps):
        mujoco.mj_step(model, data)
        angles[step] = data.qpos[hinge]
    mujoco_period = swing_period(angles, model.opt.timestep)

    world = rebond.World.from_scene(path)
    names = world.body_names()
    masses = world.masses()
    masses[names.index("cart")] *= 1e6
    world.set_masses(np.where(masses > 0, masses, 1.0))  # static bodies read 0 and ignore it
    world.set_gravity(-world.gravity())
    column = world.joint_names().index("hinge")
    positions = world.joint_positions()
    positions[column] = amplitude
    world.set_joint_positions(positions)
    steps = int(round(seconds / world.timestep))
    angles = np.empty(steps)
    zeros = np.zeros(len(world.actuator_names()))
    for step in range(steps):
        world.set_controls(zeros)
        world.step(1)
        angles[step] = world.joint_positions()[column]
    rebond_period = swing_period(angles, world.timestep)

    mass = model.body_mass[pole]
    arm = np.linalg.norm(model.body_ipos[pole])
    turn = np.zeros(9)
    mujoco.mju_quat2Mat(turn, model.body_iquat[pole])
    turn = turn.reshape(3, 3)
    axis = model.jnt_axis[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "hinge")]
    principal = turn.T @ axis
    inertia = float(principal @ np.diag(model.body_inertia[pole]) @ principal)
    inertia += mass * (arm**2 - float(axis @ model.body_ipos[pole]) ** 2)
    gravity = float(np.linalg.norm(model.opt.gravity))
    dof = model.jnt_dofadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "hinge")]
    inertia += model.dof_armature[dof]
    decay = model.dof_damping[dof] / (2 * inertia)
    analytic = 2 * np.pi / np.sqrt(mass * gravity * arm / inertia - decay**2)
    return {"rebond": rebond_period, "mujoco": mujoco_period, "analytic": float(analytic)}


def commit() -> str:
    try:
        return subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], cwd=HERE, capture_output=True, text=True
        ).stdout.strip()
    except OSError:
        return ""


def main() -> None:
    parser = argparse.ArgumentParser(description="Gymnasium's MuJoCo models: rebond and MuJoCo")
    parser.add_argument("--seconds", type=float, default=5.0)
    args = parser.parse_args()
    import mujoco

    import rebond
    from rebond.mujoco_tasks import TASKS

    cpu = cpu_name()
    print(f"CPU: {cpu}; rebond {rebond.__version__}, mujoco {mujoco.__version__}")
    print(f"Zero controls for {args.seconds:g} s from the file's pose.\n")
    print("| model | dt (s) | height rebond | height MuJoCo | speed rebond | speed MuJoCo "
          "| limit excess rebond | limit excess MuJoCo | steps/s rebond | steps/s MuJoCo |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for task in TASKS:
        result = run_model(task, args.seconds)
        rows.append((task, result))
        print(
            f"| {task} | {result['timestep']:g} | {result['rebond_height']:.3f} "
            f"| {result['mujoco_height']:.3f} | {result['rebond_speed']:.1e} "
            f"| {result['mujoco_speed']:.1e} | {result['rebond_excess']:.1e} "
            f"| {result['mujoco_excess']:.1e} | {result['rebond_steps_per_s']:,.0f} "
            f"| {result['mujoco_steps_per_s']:,.0f} |"
        )
    periods = pendulum_periods(max(args.seconds, 10.0))
    print("\n| InvertedPendulum pole period (gravity up, cart held) | rebond | MuJoCo | damped rigid "
          "pendulum |")
    print("|---|---|---|---|")
    print(f"| 0.05 rad swing (s) | {periods['rebond']:.4f} | {periods['mujoco']:.4f} "
          f"| {periods['analytic']:.4f} |")

    today = datetime.date.today().isoformat()
    slug = "-".join(cpu.lower().replace("(r)", "").replace("(tm)", "").split()[:3])
    folder = os.path.join(HERE, "results")
    path = os.path.join(folder, f"{today}-mujoco-models-{slug}.csv")
    head = ["date", "commit", "cpu", "mujoco_version", "seconds", "model", "timestep",
            "rebond_height", "mujoco_height", "rebond_speed", "mujoco_speed", "rebond_excess",
            "mujoco_excess", "rebond_steps_per_s", "mujoco_steps_per_s"]
    with open(path, "w", newline="", encoding="utf-8") as file:
        writer = csv.writer(file)
        writer.writerow(head)
        for task, result in rows:
            writer.writerow([today, commit(), cpu, mujoco.__version__, args.seconds, task]
                            + [f"{result[key]:.6g}" for key in head[6:]])
        writer.writerow([today, commit(), cpu, mujoco.__version__, args.seconds,
                         "InvertedPendulum period (rebond, MuJoCo, damped rigid pendulum)", "",
                         f"{periods['rebond']:.6g}", f"{periods['mujoco']:.6g}",
                         f"{periods['analytic']:.6g}", "", "", "", "", ""])
    print(f"\nWritten {os.path.relpath(path)}")


if __name__ == "__main__":
    main()
