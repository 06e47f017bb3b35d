"""The Hat controller's policy network (DiffCloth Sec. 6.5): two fully connected hidden layers of
64 units with tanh, float64. The last layer starts at zero, so an untrained policy's output is 0
(HatTask.next_targets: the end effectors hold still)."""

import torch as _torch


class Policy(_torch.nn.Module):
    def __init__(self, state_size, action_size, hidden=64, seed=0):
        super().__init__()
        generator_state = _torch.random.get_rng_state()
        _torch.manual_seed(seed)
        self.net = _torch.nn.Sequential(
            _torch.nn.Linear(state_size, hidden), _torch.nn.Tanh(),
            _torch.nn.Linear(hidden, hidden), _torch.nn.Tanh(),
            _torch.nn.Linear(hidden, action_size)).double()
        _torch.nn.init.zeros_(self.net[-1].weight)
        _torch.nn.init.zeros_(self.net[-1].bias)
        _torch.random.set_rng_state(generator_state)

    def forward(self, state):
        return self.net(state)

    def parameter_count(self):
        return sum(p.numel() for p in self.parameters())
