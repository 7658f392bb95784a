"""Visual Hide and Seek from Python: the game's C++ core as environments with Gymnasium's interface.

    import hideseek
    envs = hideseek.make_vec("basic", num_envs=16, seed=0)
    obs, infos = envs.reset(seed=0)                      # obs: uint8 [16, 84, 84, 3]
    obs, rewards, terminations, truncations, infos = envs.step(envs.action_space.sample())

No ROS master is needed; the workspace's setup.bash must be sourced (or config_dir= given).
"""

from .env import (ACTIONS, HAVE_GYMNASIUM, OUTCOME_CAPTURED, OUTCOME_SURVIVED, SCRIPTED_HIDERS, AutoresetMode,
                  HideSeekEnv, HideSeekVecEnv, make, make_vec)
from ._core import ConfigError

__all__ = ["ACTIONS", "HAVE_GYMNASIUM", "OUTCOME_CAPTURED", "OUTCOME_SURVIVED", "SCRIPTED_HIDERS", "AutoresetMode",
           "ConfigError", "HideSeekEnv", "HideSeekVecEnv", "make", "make_vec"]
