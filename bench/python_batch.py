"""Environment steps per second for a batch of 1,000 cart-poles: rebond's Python bindings against
MuJoCo's (the `mujoco` package on PyPI) on the same cart-pole. Not a test; see BENCHMARKS.md.

    pip install ./crates/rebond-py mujoco gymnasium
    python bench/python_batch.py [--envs 1000] [--steps 500]

Both models: a 1 kg cart on a slider along x, a 0.1 kg capsule pole (radius 0.05 m, 1 m long)
on a hinge at the cart's centre, no contacts, a 0.02 s environment step, +-10 N pushes chosen at
random every step. rebond solves each step in 4 substeps (`examples/cartpole.py`); MuJoCo is
timed with one 0.02 s step and with four 0.005 s steps per environment step.

Rows:
  rebond Batch env loop  rebond.gym.VectorEnv.step: apply_forces, Batch.step (parallel), the
                         four getters, observations, rewards and autoresets of finished
                         episodes with their final observations: a full vectorised env step
  rebond Batch.step      the parallel step alone
  rebond Batch.rollout   Batch.rollout with the random pushes given up front as a torque motor
                         on the rail (a force along it), every state of every step recorded
                         (positions, rotations, velocities, joint coordinates), no reset:
                         the counterpart of mujoco.rollout
  mujoco python loop     one MjData per env, ctrl set and mj_step called from Python, qpos and
                         qvel read: what a Gymnasium vector env over MuJoCo does
  mujoco rollout         mujoco.rollout (C++ threads, one MjData per core) with the random
                         controls given up front, no observation or reset: MuJoCo's best case
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples"))

from cartpole import cartpole_scene, make_vector_env  # noqa: E402

MJCF = """
<mujoco model="cartpole">
  <option timestep="{timestep}" gravity="0 0 -9.81"/>
  <worldbody>
    <body name="cart">
      <joint name="slider" type="slide" axis="1 0 0"/>
      <geom type="box" size="0.25 0.15 0.125" mass="1" contype="0" conaffinity="0"/>
      <body name="pole">
        <joint name="hinge" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0.05 0 0 0.95" size="0.05" mass="0.1"
              contype="0" conaffinity="0"/>
      </body>
    </body>
  </worldbody>
  <actuator><motor joint="slider" gear="1" ctrllimited="false"/></actuator>
</mujoco>
"""


def cpu_name() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as info:
            for line in info:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def best_rate(run, steps: int, envs: int, rounds: int = 3) -> float:
    """Env steps per second: the best of `rounds` timed runs of `steps` batch steps."""
    best = float("inf")
    for _ in range(rounds):
        start = time.perf_counter()
        run(steps)
        best = min(best, time.perf_counter() - start)
    return steps * envs / best


def rebond_rows(envs: int, steps: int) -> list[tuple[str, float]]:
    vector_env = make_vector_env(envs)
    vector_env.reset(seed=0)
    rng = np.random.default_rng(0)
    actions = rng.integers(0, 2, size=(steps, envs))

    def env_loop(count: int) -> None:
        for step in range(count):
            vector_env.step(actions[step % steps])

    def raw_step(count: int) -> None:
        vector_env.batch.step(count)

    import rebond

    scene = cartpole_scene()
    for joint in scene["joints"]:
        if joint["name"] == "rail":
            joint["motor"] = {"torque": 0.0}
    pushed = rebond.Batch(scene, envs)
    controls = np.where(actions == 1, 10.0, -10.0).astype(np.float32)[:, :, None]

    def rollout(count: int) -> None:
        pushed.rollout(controls[:count])

    env_loop(20)
    return [
        ("rebond Batch env loop", best_rate(env_loop, steps, envs)),
        ("rebond Batch.step", best_rate(raw_step, steps, envs)),
        ("rebond Batch.rollout", best_rate(rollout, steps, envs)),
    ]


def mujoco_rows(envs: int, steps: int) -> list[tuple[str, float]]:
    import mujoco
    from mujoco import rollout

    rows = []
    for timestep, substeps in [(0.02, 1), (0.005, 4)]:
        model = mujoco.MjModel.from_xml_string(MJCF.format(timestep=timestep))
        datas = [mujoco.MjData(model) for _ in range(envs)]
        rng = np.random.default_rng(0)
        pushes = np.where(rng.integers(0, 2, size=(steps, envs)) == 1, 10.0, -10.0)
        for data in datas:
            data.qvel[:] = rng.uniform(-0.05, 0.05, size=2)

        def python_loop(count: int) -> None:
            for step in range(count):
                row = pushes[step % steps]
                for index, data in enumerate(datas):
                    data.ctrl[0] = row[index]
                    for _ in range(substeps):
                        mujoco.mj_step(model, data)
                    observation = (data.qpos[0], data.qvel[0], data.qpos[1], data.qvel[1])
                    if abs(observation[0]) > 2.4 or abs(observation[2]) > 0.2095:
                        mujoco.mj_resetData(model, data)

        label = f"mujoco python loop, {substeps} x {timestep} s"
        rows.append((label, best_rate(python_loop, max(steps // 10, 5), envs)))

        threads = os.cpu_count() or 1
        thread_datas = [mujoco.MjData(model) for _ in range(threads)]
        state_spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
        initial = np.zeros((envs, mujoco.mj_stateSize(model, state_spec)))
        for index in range(envs):
            mujoco.mj_getState(model, datas[index], initial[index], state_spec)
        controls = np.repeat(pushes.T[:, :, None], substeps, axis=1)  # (envs, steps*substeps, 1)

        def threaded_rollout(count: int) -> None:
            rollout.rollout(model, thread_datas, initial, controls[:, : count * substeps])

        label = f"mujoco rollout ({threads} threads), {substeps} x {timestep} s"
        rows.append((label, best_rate(threaded_rollout, steps, envs)))
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description="cart-pole batch: rebond against MuJoCo")
    parser.add_argument("--envs", type=int, default=1000)
    parser.add_argument("--steps", type=int, default=500)
    args = parser.parse_args()
    import mujoco

    import rebond

    print(f"CPU: {cpu_name()} ({os.cpu_count()} cores seen)")
    print(f"rebond {rebond.__version__}, mujoco {mujoco.__version__}, numpy {np.__version__}")
    print(f"{args.envs} cart-poles, {args.steps} env steps of 0.02 s, best of 3")
    rows = rebond_rows(args.envs, args.steps) + mujoco_rows(args.envs, args.steps)
    for label, rate in rows:
        print(f"  {label:<44} {rate:>12,.0f} env steps/s")


if __name__ == "__main__":
    main()
