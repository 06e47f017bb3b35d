"""`python3 -m weft.bench hat_controller`: the Hat controller trained through the simulator (Adam)
against PPO on the same task (DiffCloth Sec. 6.5, Fig. 12), evaluated from 20 fixed test starts.

Writes into --out (default bench-out/hat_controller): adam_policy.pt (the trained weights,
torch.save of the Policy's state_dict, written as soon as Adam is done), curve.csv (training loss against simulated
steps, both methods), test.csv (each test start: elevation, azimuth, L, success, mean distance to
the target), summary.json and summary.md (the figures docs/python.md quotes), curve.png (L
against simulated steps, log scale: Adam blue, PPO orange, PPO's running mean of 5 batches in
dark orange) and trajectories.png (the trained Adam policy's end-effector midpoint from ten test
starts: side view x-y left, top view x-z right, the head grey, starts marked)."""

import argparse
import csv
import json
import os
import platform
import sys
import time

import numpy as np
import torch

from weft.bench.canvas import Axes, Canvas
from weft.hat.adam import evaluate, train_adam, wait_politely
from weft.hat.policy import Policy
from weft.hat.ppo import evaluate_ppo, train_ppo
from weft.hat.task import HatTask, elevation_azimuth_deg, hemisphere_starts

TEST_SEED = 20220  # the 20 fixed test starts


def parse(argv):
    p = argparse.ArgumentParser(prog="python3 -m weft.bench hat_controller",
                                description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=os.path.join("bench-out", "hat_controller"))
    p.add_argument("--epochs", type=int, default=40, help="Adam epochs (default 40)")
    p.add_argument("--starts", type=int, default=20, help="random starts per epoch (default 20)")
    p.add_argument("--steps", type=int, default=None,
                   help="steps per rollout (default: hat_controller.json's, 50)")
    p.add_argument("--dt", type=float, default=None,
                   help="time step, s (default: hat_controller.json's, 0.02)")
    p.add_argument("--lr", type=float, default=3e-3, help="Adam's learning rate (default 3e-3)")
    p.add_argument("--ppo-steps", type=int, default=None,
                   help="PPO's budget of simulated steps (default: 10 times Adam's)")
    p.add_argument("--tests", type=int, default=20, help="fixed test starts (default 20)")
    p.add_argument("--no-ppo", action="store_true", help="train with Adam only")
    return p.parse_args(argv)


def log_line(method):
    def log(record):
        print(f"{method}: " + ", ".join(f"{k} {v:.4g}" if isinstance(v, float) else f"{k} {v}"
                                        for k, v in record.items()), flush=True)
    return log


def first_reaching(records, level):
    """Simulated steps at which a record's training loss first reaches `level`, else None."""
    for r in records:
        if r["train_loss"] <= level:
            return r["simulated_steps"]
    return None


def running_mean(values, window):
    out = []
    for k in range(len(values)):
        part = values[max(0, k - window + 1):k + 1]
        out.append(sum(part) / len(part))
    return out


def draw_curve(path, adam, ppo):
    canvas = Canvas(900, 500)
    all_steps = [r["simulated_steps"] for r in adam + ppo]
    losses = [r["train_loss"] for r in adam + ppo]
    axes = Axes(canvas, 60, 20, 820, 440, (min(all_steps) * 0.8, max(all_steps) * 1.25),
                (0.0, max(losses) * 1.05), log_u=True)
    axes.frame()
    if ppo:
        axes.polyline([r["simulated_steps"] for r in ppo], [r["train_loss"] for r in ppo],
                      (250, 190, 120), 1.0)
        axes.polyline([r["simulated_steps"] for r in ppo],
                      running_mean([r["train_loss"] for r in ppo], 5), (210, 110, 20), 2.0)
    axes.polyline([r["simulated_steps"] for r in adam], [r["train_loss"] for r in adam],
                  (40, 90, 200), 2.0)
    canvas.save(path)


def draw_trajectories(path, task, directions, results):
    canvas = Canvas(1000, 500)
    r = task.radius * 1.3
    side = Axes(canvas, 20, 20, 460, 460, (-r, r), (-r * 0.5, r * 1.5))
    top = Axes(canvas, 520, 20, 460, 460, (-r, r), (-r, r))
    for axes in (side, top):
        axes.frame()
    side.circle(0.0, 0.0, 0.1, (150, 150, 150))
    top.circle(0.0, 0.0, 0.1, (150, 150, 150))
    colours = [(31, 119, 180), (255, 127, 14), (44, 160, 44), (214, 39, 40), (148, 103, 189),
               (140, 86, 75), (227, 119, 194), (127, 127, 127), (188, 189, 34), (23, 190, 207)]
    for k, (d, result) in enumerate(zip(directions, results)):
        mid = result[3].mean(axis=1)  # [steps + 1, 3]: the end effectors' midpoint
        colour = colours[k % len(colours)]
        side.polyline(mid[:, 0], mid[:, 1], colour)
        top.polyline(mid[:, 0], mid[:, 2], colour)
        side.dot(mid[0, 0], mid[0, 1], colour)
        top.dot(mid[0, 0], mid[0, 2], colour)
    canvas.save(path)


def end_together():
    """Under mpirun: every rank waits here, with sleeps, until rank 0 is done (mpi4py's
    MPI_Finalize at exit would otherwise keep the other ranks polling a core each)."""
    try:
        from mpi4py import MPI
    except ImportError:
        return
    if MPI.COMM_WORLD.Get_size() > 1:
        wait_politely(MPI.COMM_WORLD.Ibarrier())


def main(argv=None):
    args = parse(argv if argv is not None else sys.argv[1:])
    torch.set_num_threads(1)
    task = HatTask(steps=args.steps, dt=args.dt)
    tests = hemisphere_starts(args.tests, TEST_SEED)
    rank = 0
    try:
        from mpi4py import MPI
        rank = MPI.COMM_WORLD.Get_rank()
    except ImportError:
        pass

    policy = Policy(task.state_size, task.action_size, seed=0)
    began = time.perf_counter()
    adam = train_adam(task, policy, args.epochs, starts_per_epoch=args.starts, lr=args.lr,
                      log=log_line("adam"))
    adam_seconds = time.perf_counter() - began
    if rank != 0:
        end_together()
        return 0
    os.makedirs(args.out, exist_ok=True)
    torch.save(policy.state_dict(), os.path.join(args.out, "adam_policy.pt"))
    adam_tests = evaluate(task, policy, tests)

    ppo, ppo_tests, ppo_seconds = [], [], 0.0
    budget = args.ppo_steps if args.ppo_steps is not None else 10 * adam[-1]["simulated_steps"]
    if not args.no_ppo:
        began = time.perf_counter()
        agent, ppo = train_ppo(task, budget, log=log_line("ppo"))
        ppo_seconds = time.perf_counter() - began
        ppo_tests = evaluate_ppo(agent, tests)

    with open(os.path.join(args.out, "curve.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["method", "index", "simulated_steps", "train_loss", "seconds"])
        for r in adam:
            w.writerow(["adam", r["epoch"], r["simulated_steps"], f"{r['train_loss']:.6g}",
                        f"{r['seconds']:.2f}"])
        for r in ppo:
            w.writerow(["ppo", r["batch"], r["simulated_steps"], f"{r['train_loss']:.6g}",
                        f"{r['seconds']:.2f}"])
    with open(os.path.join(args.out, "test.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["method", "start", "elevation_deg", "azimuth_deg", "loss", "success",
                    "mean_distance_m"])
        for method, results in (("adam", adam_tests), ("ppo", ppo_tests)):
            for k, (d, res) in enumerate(zip(tests, results)):
                el, az = elevation_azimuth_deg(d)
                w.writerow([method, k, f"{el:.1f}", f"{az:.1f}", f"{res[0]:.6g}", int(res[1]),
                            f"{res[2]:.4f}"])

    adam_final = adam[-1]["train_loss"]
    ppo_best = min((r["train_loss"] for r in ppo), default=None)
    ppo_reach = first_reaching(ppo, adam_final) if ppo else None
    summary = {
        "machine": f"{platform.machine()}, {os.cpu_count()} cores; torch {torch.__version__}, "
                   f"1 thread",
        "task": {"steps": task.steps, "dt": task.dt, "vertices": int(task.rest.shape[0]),
                 "radius": task.radius, "max_speed": task.max_speed,
                 "state_size": task.state_size, "policy_parameters": policy.parameter_count()},
        "adam": {"epochs": args.epochs, "starts_per_epoch": args.starts, "lr": args.lr,
                 "simulated_steps": adam[-1]["simulated_steps"], "initial_train_loss":
                 adam[0]["train_loss"], "final_train_loss": adam_final,
                 "test_mean_loss": float(np.mean([r[0] for r in adam_tests])),
                 "test_successes": int(sum(r[1] for r in adam_tests)),
                 "seconds": adam_seconds},
    }
    if ppo:
        summary["ppo"] = {
            "step_budget": budget, "simulated_steps": ppo[-1]["simulated_steps"],
            "initial_train_loss": ppo[0]["train_loss"],
            "final_train_loss_mean_of_last_5": float(np.mean([r["train_loss"] for r in ppo[-5:]])),
            "best_batch_train_loss": ppo_best,
            "steps_to_reach_adam_final_loss": ppo_reach,
            "test_mean_loss": float(np.mean([r[0] for r in ppo_tests])),
            "test_successes": int(sum(r[1] for r in ppo_tests)), "seconds": ppo_seconds}
        summary["speedup_in_steps"] = (ppo_reach / adam[-1]["simulated_steps"]) if ppo_reach \
            else None
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
    lines = ["| method | simulated steps | training L, first | last | test L (mean of "
             f"{args.tests}) | test successes | seconds |", "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    a = summary["adam"]
    lines.append(f"| Adam through the simulator | {a['simulated_steps']:,} | "
                 f"{a['initial_train_loss']:.3f} | {a['final_train_loss']:.3f} | "
                 f"{a['test_mean_loss']:.3f} | {a['test_successes']}/{args.tests} | "
                 f"{a['seconds']:.0f} |")
    if ppo:
        p = summary["ppo"]
        lines.append(f"| PPO | {p['simulated_steps']:,} | {p['initial_train_loss']:.3f} | "
                     f"{p['final_train_loss_mean_of_last_5']:.3f} (mean of the last 5 batches) | "
                     f"{p['test_mean_loss']:.3f} | {p['test_successes']}/{args.tests} | "
                     f"{p['seconds']:.0f} |")
        lines.append("")
        lines.append(
            f"PPO reached Adam's final training loss ({adam_final:.3f}) after {ppo_reach:,} steps "
            f"({summary['speedup_in_steps']:.1f} times Adam's)." if ppo_reach else
            f"PPO did not reach Adam's final training loss ({adam_final:.3f}) within "
            f"{p['simulated_steps']:,} steps; its best batch was {ppo_best:.3f}.")
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    draw_curve(os.path.join(args.out, "curve.png"), adam, ppo)
    draw_trajectories(os.path.join(args.out, "trajectories.png"), task, tests[:10],
                      adam_tests[:10])
    print("\n".join(lines))
    print(f"written to {args.out}")
    end_together()
    return 0


if __name__ == "__main__":
    sys.exit(main())
