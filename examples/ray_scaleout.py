"""Cart-poles spread over a Ray cluster: remote actors, each owning a ``rebond.Batch``.

Each actor holds a batch of cart-poles (``cartpole.make_vector_env``, a Gymnasium vector
environment over a ``rebond.Batch``) and steps it with random
pushes; the driver starts the actors, runs them at once, and adds up what they did. Within an
actor the batch steps on all the cores Ray gives it (rebond uses a thread pool the size of
``RAYON_NUM_THREADS``, which the actor sets to its ``num_cpus``).

On one machine:

    python examples/ray_scaleout.py --actors 2 --worlds 500 --steps 200

On a cluster, start Ray on every machine (``ray start --head`` on one, ``ray start
--address=HEAD:6379`` on the others), install rebond on each (``pip install ./crates/rebond-py``),
then run the driver with ``RAY_ADDRESS=auto``, one actor per machine with all its cores:

    RAY_ADDRESS=auto python examples/ray_scaleout.py --actors 8 --cpus-per-actor 32 --worlds 4000
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from typing import Any

import numpy as np
import ray

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


class BatchWorker:
    """One actor's share: a batch of cart-poles and a random-number generator of its own."""

    def __init__(self, worlds: int, seed: int, threads: int) -> None:
        # rebond's thread pool starts at the first parallel call: size it to this actor's cores.
        os.environ.setdefault("RAYON_NUM_THREADS", str(threads))
        from cartpole import make_vector_env

        self.envs = make_vector_env(worlds)
        self.envs.reset(seed=seed)
        self.episodes = 0
        self.rng = np.random.default_rng(seed)

    def run(self, steps: int) -> dict[str, Any]:
        """Steps every world ``steps`` times with random pushes; returns counts and the final
        observations' checksum, so that the driver can check runs against each other."""
        start = time.perf_counter()
        observation = None
        for _ in range(steps):
            actions = self.rng.integers(0, 2, size=self.envs.num_envs)
            observation, _, terminated, truncated, _ = self.envs.step(actions)
            self.episodes += int(np.sum(terminated | truncated))
        seconds = time.perf_counter() - start
        return {
            "env_steps": steps * self.envs.num_envs,
            "episodes": self.episodes,
            "seconds": seconds,
            "checksum": float(np.sum(np.abs(observation))) if observation is not None else 0.0,
        }


def run(actors: int, worlds: int, steps: int, cpus_per_actor: int = 1) -> dict[str, Any]:
    """Runs ``actors`` remote batches of ``worlds`` cart-poles for ``steps`` steps each on the
    Ray cluster already initialised; returns the totals and each actor's result."""
    remote = ray.remote(num_cpus=cpus_per_actor)(BatchWorker)
    handles = [remote.remote(worlds, seed, cpus_per_actor) for seed in range(actors)]
    start = time.perf_counter()
    results = ray.get([handle.run.remote(steps) for handle in handles])
    seconds = time.perf_counter() - start
    for handle in handles:
        ray.kill(handle)
    env_steps = sum(result["env_steps"] for result in results)
    return {
        "env_steps": env_steps,
        "episodes": sum(result["episodes"] for result in results),
        "seconds": seconds,
        "env_steps_per_second": env_steps / seconds,
        "actors": results,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--actors", type=int, default=2)
    parser.add_argument("--worlds", type=int, default=500, help="cart-poles per actor")
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--cpus-per-actor", type=int, default=1)
    args = parser.parse_args()
    ray.init(address=os.environ.get("RAY_ADDRESS"))
    totals = run(args.actors, args.worlds, args.steps, args.cpus_per_actor)
    print(
        f"{args.actors} actors x {args.worlds} cart-poles x {args.steps} steps: "
        f"{totals['env_steps']} env steps, {totals['episodes']} episodes, "
        f"{totals['env_steps_per_second']:,.0f} env steps/s"
    )
    ray.shutdown()


if __name__ == "__main__":
    main()
