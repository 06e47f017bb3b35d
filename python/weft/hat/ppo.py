"""PPO (Schulman et al. 2017) on the Hat controller's task, written here in PyTorch (Debian has no
RL library): the gradient-free baseline of DiffCloth Sec. 6.5.

Same observation (HatTask.state), same action map (HatTask.next_targets) and same network shape
as the policy trained through the simulator; the actor's output o is Gaussian with a learned,
state-independent log standard deviation. Reward per step r_n = reward_constant - (state n's
share of L) (HatTask.step_loss), so an episode's return is steps * reward_constant - L (Sec. 6.5:
"the negative counterpart of L plus a constant"). Clipped surrogate, generalised advantage
estimation, a separate critic of the same shape, observations normalised by running statistics.
The simulator's steps are forward only."""

import time as _time

import numpy as _np
import torch as _torch

from .policy import Policy
from .task import hemisphere_starts


class _RunningNormaliser:
    def __init__(self, size):
        self.count, self.mean, self.m2 = 0, _np.zeros(size), _np.zeros(size)

    def update(self, batch):
        for row in batch:
            self.count += 1
            delta = row - self.mean
            self.mean += delta / self.count
            self.m2 += delta * (row - self.mean)

    def __call__(self, obs):
        std = _np.sqrt(self.m2 / max(1, self.count - 1)) + 1e-8 if self.count > 1 else 1.0
        return _np.clip((obs - self.mean) / std, -10, 10)


class PpoAgent:
    def __init__(self, task, seed=0, log_std=-0.5):
        self.task = task
        self.actor = Policy(task.state_size, task.action_size, seed=seed)
        self.critic = Policy(task.state_size, 1, seed=seed + 1)
        _torch.nn.init.normal_(self.critic.net[-1].weight, std=0.01)
        self.log_std = _torch.nn.Parameter(_torch.full((task.action_size,), log_std,
                                                       dtype=_torch.float64))
        self.normaliser = _RunningNormaliser(task.state_size)

    def distribution(self, obs):
        return _torch.distributions.Normal(self.actor(obs), self.log_std.exp())

    def episode(self, direction, rng, deterministic=False):
        """One episode from `direction`: observations, outputs, log-probabilities, rewards, L."""
        task = self.task
        sim = task.simulator(direction)
        base = _torch.as_tensor(task.initial_targets(direction))
        targets = base.clone()
        x = _torch.as_tensor(sim.positions)
        observations, outputs, log_probs, rewards, total = [], [], [], [], 0.0
        with _torch.no_grad():
            for n in range(1, task.steps + 1):
                raw = task.state(x, targets).numpy()
                obs = _torch.as_tensor(self.normaliser(raw))
                dist = self.distribution(obs)
                if deterministic:
                    out = dist.mean
                else:
                    out = dist.mean + dist.stddev * _torch.as_tensor(
                        rng.standard_normal(task.action_size))
                targets = task.next_targets(targets, out)
                sim.drive_handles((targets - base).numpy())
                sim.step()
                x = _torch.as_tensor(sim.positions)
                share = float(task.step_loss(n, x))
                observations.append(raw)
                outputs.append(out.numpy())
                log_probs.append(float(dist.log_prob(out).sum()))
                rewards.append(share)
                total += share
        return observations, outputs, log_probs, rewards, total, x.numpy()


def train_ppo(task, step_budget, episodes_per_batch=4, update_epochs=10, minibatch=64, lr=3e-4,
              clip=0.2, gamma=0.99, lam=0.95, reward_constant=10.0, seed=2, log=None):
    """PPO until `step_budget` simulated steps. Returns one record per batch: batch,
    simulated_steps, train_loss (the batch's mean episode L, its actions sampled), seconds."""
    agent = PpoAgent(task, seed=seed)
    rng = _np.random.default_rng(seed)
    optimizer = _torch.optim.Adam(
        list(agent.actor.parameters()) + [agent.log_std] + list(agent.critic.parameters()), lr=lr)
    records, steps, batch_index, start_time = [], 0, 0, _time.perf_counter()
    while steps < step_budget:
        starts = hemisphere_starts(episodes_per_batch, seed * 1_000_003 + batch_index)
        obs_raw, outs, old_logp, advantages, returns, losses = [], [], [], [], [], []
        for d in starts:
            o, a, lp, shares, total, _ = agent.episode(d, rng)
            rewards = reward_constant - _np.asarray(shares)
            with _torch.no_grad():
                normalised = _torch.as_tensor(_np.stack([agent.normaliser(r) for r in o]))
                values = agent.critic(normalised).squeeze(-1).numpy()
            gae, adv = 0.0, _np.zeros(len(rewards))
            for n in reversed(range(len(rewards))):
                next_value = values[n + 1] if n + 1 < len(rewards) else 0.0
                delta = rewards[n] + gamma * next_value - values[n]
                gae = delta + gamma * lam * gae
                adv[n] = gae
            obs_raw += o
            outs += a
            old_logp += lp
            advantages.append(adv)
            returns.append(adv + values)
            losses.append(total)
            steps += task.steps
        agent.normaliser.update(_np.stack(obs_raw))
        obs = _torch.as_tensor(_np.stack([agent.normaliser(r) for r in obs_raw]))
        acts = _torch.as_tensor(_np.stack(outs))
        logp0 = _torch.as_tensor(old_logp)
        adv = _torch.as_tensor(_np.concatenate(advantages))
        adv = (adv - adv.mean()) / (adv.std() + 1e-8)
        ret = _torch.as_tensor(_np.concatenate(returns))
        count = len(obs)
        for _ in range(update_epochs):
            order = _torch.as_tensor(rng.permutation(count))
            for first in range(0, count, minibatch):
                idx = order[first:first + minibatch]
                dist = agent.distribution(obs[idx])
                ratio = (dist.log_prob(acts[idx]).sum(-1) - logp0[idx]).exp()
                surrogate = _torch.min(ratio * adv[idx],
                                       ratio.clamp(1 - clip, 1 + clip) * adv[idx])
                value_loss = (agent.critic(obs[idx]).squeeze(-1) - ret[idx]).pow(2).mean()
                loss = -surrogate.mean() + 0.5 * value_loss
                optimizer.zero_grad()
                loss.backward()
                _torch.nn.utils.clip_grad_norm_(optimizer.param_groups[0]["params"], 0.5)
                optimizer.step()
        batch_index += 1
        record = {"batch": batch_index, "simulated_steps": steps,
                  "train_loss": float(_np.mean(losses)),
                  "seconds": _time.perf_counter() - start_time}
        records.append(record)
        if log:
            log(record)
    return agent, records


def evaluate_ppo(agent, directions):
    """The PPO policy's mean action from each start: (L, success, mean distance, None) each."""
    results = []
    for d in directions:
        _, _, _, _, total, x = agent.episode(d, None, deterministic=True)
        ok, distance = agent.task.success(x)
        results.append((total, ok, distance, None))
    return results
