#!/usr/bin/env python3
"""PPO from pixels on Visual Hide and Seek in one file, CleanRL-style (ppo_atari), with PyTorch and the
hideseek module: no ROS master, no C++ trainer. The network is the paper's (the C++ hider's layer for
layer, with its parameter names), the hyperparameters config/ppo.yaml's, so that its learning curve
can be laid beside the C++ trainer's for the same steps.

    source devel/setup.bash
    /usr/bin/python3 examples/ppo_python.py --steps 122880 --out /tmp/ppo_python
    # the policy in the project's checkpoint format (recording the game it trained on), played in rviz:
    rosrun hideseek_hider import_policy /tmp/ppo_python/policy_torchscript.pt /tmp/ppo_python/policy.pt basic
    roslaunch hideseek_world basic.launch policy:=/tmp/ppo_python/policy.pt

Writes OUT/training_log.csv with the C++ trainer's columns (plot_learning_curve.py draws both) and
OUT/policy_torchscript.pt (TorchScript: what import_policy reads).
"""
import argparse
import csv
import os
import time
from collections import deque

import numpy as np
import torch
import torch.nn as nn
import torch.nn.functional as F
import yaml

import hideseek


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--variant", default="basic")
    p.add_argument("--game", default=None, help="v3, v2 or v1 (default: config/games.yaml's); give import_policy "
                   "the same --game")
    p.add_argument("--seed", type=int, default=0, help="training seed: torch's and the first episode seed")
    p.add_argument("--num-envs", type=int, default=16)
    p.add_argument("--steps", type=int, default=122880, help="environment steps to train")
    p.add_argument("--schedule-steps", type=int, default=2000000,
                   help="steps the learning rate anneals over (the C++ sweep's 2M, so that a short run "
                        "follows the same schedule)")
    p.add_argument("--ppo-config", default=None, help="PPO hyperparameters (default: the package's ppo.yaml)")
    p.add_argument("--precision", choices=["fp32", "bf16"], default="fp32",
                   help="bf16 autocasts the network's passes (useful only where the CPU has native bf16)")
    p.add_argument("--threads", type=int, default=2, help="torch intra-op threads")
    p.add_argument("--out", required=True, help="folder for training_log.csv and policy_torchscript.pt")
    return p.parse_args()


class Agent(nn.Module):
    """The paper's network: three convolutions to 512 features, an actor and a critic head of 512
    units each; leaky ReLU (0.01). Images are uint8 [B, 84, 84, 3], scaled to [0, 1] here."""

    def __init__(self, height=84, width=84, actions=5):
        super().__init__()
        self.conv1 = nn.Conv2d(3, 32, 8, stride=4)
        self.conv2 = nn.Conv2d(32, 64, 4, stride=2)
        self.conv3 = nn.Conv2d(64, 64, 3, stride=1)
        h, w = height, width
        for k, s in ((8, 4), (4, 2), (3, 1)):
            h, w = (h - k) // s + 1, (w - k) // s + 1
        self.features = nn.Linear(64 * h * w, 512)
        self.actor_hidden = nn.Linear(512, 512)
        self.actor_out = nn.Linear(512, actions)
        self.critic_hidden = nn.Linear(512, 512)
        self.critic_out = nn.Linear(512, 1)

    def forward(self, images):
        x = images.permute(0, 3, 1, 2).float() / 255.0
        x = F.leaky_relu(self.conv1(x), 0.01)
        x = F.leaky_relu(self.conv2(x), 0.01)
        x = F.leaky_relu(self.conv3(x), 0.01)
        x = F.leaky_relu(self.features(x.flatten(1)), 0.01)
        logits = self.actor_out(F.leaky_relu(self.actor_hidden(x), 0.01).float())
        value = self.critic_out(F.leaky_relu(self.critic_hidden(x), 0.01).float()).squeeze(-1)
        return logits.float(), value.float()


def main():
    args = parse_args()
    cfg = yaml.safe_load(open(args.ppo_config or os.path.join(hideseek._core.config_directory(), "ppo.yaml")))
    torch.manual_seed(args.seed)
    torch.set_num_threads(args.threads)
    os.makedirs(args.out, exist_ok=True)
    autocast = torch.autocast("cpu", dtype=torch.bfloat16, enabled=args.precision == "bf16")

    envs = hideseek.make_vec(args.variant, num_envs=args.num_envs, seed=args.seed, game=args.game)
    print("ppo_python: %s on game %s" % (args.variant, envs.game))
    agent = Agent(envs.single_observation_space.shape[0], envs.single_observation_space.shape[1])
    optimizer = torch.optim.Adam(agent.parameters(), lr=cfg["learning_rate"], eps=cfg["adam_epsilon"])

    T, N = cfg["rollout_steps"], args.num_envs
    batch = T * N
    minibatch = batch // cfg["minibatches"]
    obs_buf = torch.zeros((T, N) + envs.single_observation_space.shape, dtype=torch.uint8)
    actions_buf = torch.zeros((T, N), dtype=torch.long)
    logprobs_buf, rewards_buf, dones_buf, values_buf = (torch.zeros((T, N)) for _ in range(4))

    obs, _ = envs.reset(seed=args.seed)
    obs = torch.from_numpy(obs)
    recent = deque(maxlen=100)  # (length, return) of the last finished episodes, as the C++ log
    running_return = np.zeros(N)
    steps, episodes, start = 0, 0, time.time()
    log = open(os.path.join(args.out, "training_log.csv"), "w", newline="")
    writer = csv.writer(log)
    writer.writerow(["update", "steps", "wall_s", "steps_per_s", "episodes", "mean_length", "mean_return",
                     "policy_loss", "value_loss", "entropy", "approx_kl", "clip_fraction", "learning_rate"])
    update = 0
    while steps < args.steps:
        update += 1
        lr = cfg["learning_rate"] * (max(0.0, 1.0 - steps / args.schedule_steps) if cfg["anneal_learning_rate"]
                                     else 1.0)
        optimizer.param_groups[0]["lr"] = lr
        # ---- rollout: T steps of N arenas ----
        for t in range(T):
            obs_buf[t] = obs
            with torch.no_grad(), autocast:
                logits, value = agent(obs)
            dist = torch.distributions.Categorical(logits=logits)
            action = dist.sample()
            actions_buf[t], logprobs_buf[t], values_buf[t] = action, dist.log_prob(action), value
            next_obs, reward, term, trunc, infos = envs.step(action.numpy())
            done = term | trunc  # a survived episode is not bootstrapped either, as in the C++ trainer
            rewards_buf[t] = torch.from_numpy(reward).float()
            dones_buf[t] = torch.from_numpy(done).float()
            running_return += reward
            for i in np.flatnonzero(done):
                recent.append((infos["final_info"]["length"][i], running_return[i]))
                running_return[i] = 0.0
                episodes += 1
            obs = torch.from_numpy(next_obs)
        steps += batch
        # ---- GAE: dones_buf[t] ends the episode at step t ----
        with torch.no_grad(), autocast:
            next_value = agent(obs)[1].float()
        advantages = torch.zeros((T, N))
        last = torch.zeros(N)
        for t in reversed(range(T)):
            nv = next_value if t == T - 1 else values_buf[t + 1]
            not_done = 1.0 - dones_buf[t]
            delta = rewards_buf[t] + cfg["gamma"] * nv * not_done - values_buf[t]
            last = delta + cfg["gamma"] * cfg["gae_lambda"] * not_done * last
            advantages[t] = last
        returns = advantages + values_buf
        b_obs, b_actions = obs_buf.flatten(0, 1), actions_buf.flatten()
        b_logprobs, b_adv = logprobs_buf.flatten(), advantages.flatten()
        b_returns, b_values = returns.flatten(), values_buf.flatten()
        # ---- update: epochs x minibatches ----
        stats = []
        for _ in range(cfg["epochs"]):
            perm = torch.randperm(batch)
            for k in range(0, batch, minibatch):
                idx = perm[k:k + minibatch]
                with autocast:
                    logits, value = agent(b_obs[idx])
                dist = torch.distributions.Categorical(logits=logits)
                logratio = dist.log_prob(b_actions[idx]) - b_logprobs[idx]
                ratio = logratio.exp()
                adv = b_adv[idx]
                if cfg["normalize_advantages"]:
                    adv = (adv - adv.mean()) / (adv.std() + 1e-8)
                pg_loss = torch.max(-adv * ratio, -adv * ratio.clamp(1 - cfg["clip"], 1 + cfg["clip"])).mean()
                if cfg["clip_value_loss"]:
                    v_clipped = b_values[idx] + (value - b_values[idx]).clamp(-cfg["clip"], cfg["clip"])
                    v_loss = 0.5 * torch.max((value - b_returns[idx]) ** 2, (v_clipped - b_returns[idx]) ** 2).mean()
                else:
                    v_loss = 0.5 * ((value - b_returns[idx]) ** 2).mean()
                entropy = dist.entropy().mean()
                loss = pg_loss + cfg["value_coef"] * v_loss - cfg["entropy_coef"] * entropy
                optimizer.zero_grad()
                loss.backward()
                nn.utils.clip_grad_norm_(agent.parameters(), cfg["max_grad_norm"])
                optimizer.step()
                with torch.no_grad():
                    approx_kl = ((ratio - 1) - logratio).mean()
                    clipfrac = ((ratio - 1.0).abs() > cfg["clip"]).float().mean()
                stats.append([pg_loss.item(), v_loss.item(), entropy.item(), approx_kl.item(), clipfrac.item()])
        wall = time.time() - start
        mean_length = np.mean([l for l, _ in recent]) if recent else 0.0
        mean_return = np.mean([r for _, r in recent]) if recent else 0.0
        s = np.mean(stats, axis=0)
        writer.writerow([update, steps, "%.3f" % wall, "%.3f" % (steps / wall), episodes, "%.6g" % mean_length,
                         "%.6g" % mean_return] + ["%.6g" % x for x in s] + ["%.6g" % lr])
        log.flush()
        if update % 10 == 0 or steps >= args.steps:
            print("update %d: %d steps, %.0f steps/s, mean length %.1f, entropy %.3f"
                  % (update, steps, steps / wall, mean_length, s[2]), flush=True)
    log.close()
    torch.jit.script(agent).save(os.path.join(args.out, "policy_torchscript.pt"))
    print("wrote %s/training_log.csv and %s/policy_torchscript.pt" % (args.out, args.out))


if __name__ == "__main__":
    main()
