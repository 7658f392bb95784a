#!/usr/bin/env python3
"""Samples/s of one PPO-shaped training step of the hider's network in three memory layouts.

The network is the paper's (three convolutions, 3136-512 trunk, 512-unit policy and value heads);
one step is forward, backward and an Adam step on a batch of 84 x 84 images, as the trainer runs it.
Layouts:
  nchw   the HWC images copied into contiguous NCHW first (what a naive port would do);
  hwc    the project's: the HWC bytes viewed as [B, 3, H, W] with permute (channels-last strides),
         weights left NCHW;
  cl     channels-last images and weights (torch.channels_last).
Run with Debian's python3-torch to match the C++ trainer's libtorch, or any PyTorch to compare CPUs.
"""
import argparse
import platform
import time

import torch

F = torch.nn.functional


class Net(torch.nn.Module):
    def __init__(self):
        super().__init__()
        self.c1 = torch.nn.Conv2d(3, 32, 8, stride=4)
        self.c2 = torch.nn.Conv2d(32, 64, 4, stride=2)
        self.c3 = torch.nn.Conv2d(64, 64, 3)
        self.trunk = torch.nn.Linear(3136, 512)
        self.pi = torch.nn.Linear(512, 512)
        self.pi_out = torch.nn.Linear(512, 5)
        self.v = torch.nn.Linear(512, 512)
        self.v_out = torch.nn.Linear(512, 1)

    def forward(self, x):
        act = lambda t: F.leaky_relu(t, 0.01)
        x = act(self.c3(act(self.c2(act(self.c1(x))))))
        x = act(self.trunk(x.flatten(1)))
        return self.pi_out(act(self.pi(x))), self.v_out(act(self.v(x)))


def samples_per_second(layout, bf16, batch, steps):
    torch.manual_seed(0)
    net = Net()
    if layout == "cl":
        net = net.to(memory_format=torch.channels_last)
    opt = torch.optim.Adam(net.parameters(), 2.5e-4)
    images = torch.randint(0, 256, (batch, 84, 84, 3), dtype=torch.uint8)

    def step():
        x = images.permute(0, 3, 1, 2).to(torch.float32).div(255.0)
        if layout == "nchw":
            x = x.contiguous()
        with torch.autocast("cpu", dtype=torch.bfloat16, enabled=bf16):
            logits, value = net(x)
        loss = logits.float().logsumexp(1).mean() + value.float().pow(2).mean()
        opt.zero_grad()
        loss.backward()
        opt.step()

    for _ in range(2):
        step()
    start = time.perf_counter()
    for _ in range(steps):
        step()
    return steps * batch / (time.perf_counter() - start)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--precision", choices=["fp32", "bf16"], default="fp32")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--batch", type=int, default=256)
    parser.add_argument("--steps", type=int, default=12)
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
    torch.set_num_threads(args.threads)
    print(f"# torch {torch.__version__}, {platform.processor() or platform.machine()}, "
          f"cpu capability {torch.backends.cpu.get_cpu_capability() if hasattr(torch.backends, 'cpu') else '?'}, "
          f"{args.threads} threads, batch {args.batch}, {args.precision}")
    for _ in range(args.repeats):
        print(" ".join(f"{layout}={samples_per_second(layout, args.precision == 'bf16', args.batch, args.steps):.0f}"
                       for layout in ["nchw", "hwc", "cl"]), flush=True)


if __name__ == "__main__":
    main()
