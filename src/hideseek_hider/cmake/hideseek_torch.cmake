# hideseek_hider's public headers (the network, checkpoints, policies, PPO) include libtorch's, and
# its libraries call into it: a package that finds hideseek_hider through catkin gets libtorch's
# include folders and libraries with it, as it gets hideseek_hider's own. libtorch's headers trip
# -Wextra; a package that builds with -Werror should also add
# include_directories(SYSTEM ${TORCH_INCLUDE_DIRS}), as this workspace's packages do.
find_package(Torch REQUIRED)
list(APPEND hideseek_hider_INCLUDE_DIRS ${TORCH_INCLUDE_DIRS})
list(APPEND hideseek_hider_LIBRARIES ${TORCH_LIBRARIES})
