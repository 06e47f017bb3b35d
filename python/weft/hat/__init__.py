"""The Hat controller (DiffCloth Sec. 6.5): task, policy, training through the simulator, PPO."""
