# The environment the ROS 2 Jazzy wheels from PyPI need to run rosbridge-server-rs and rclpy
# nodes out of tests/ros/.venv (made by scripts/install-test-deps.sh); see
# ../shared/notes/robot.md. Source it (`. tests/ros/env.sh`), or run a command through
# tests/ros/run.sh. ROS_DOMAIN_ID is the caller's: every test sets its own.
ros_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
venv="$ros_dir/.venv"
site="$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
libpython="$("$venv/bin/python" -c 'import sysconfig, os; print(os.path.join(sysconfig.get_config_var("LIBDIR"), sysconfig.get_config_var("LDLIBRARY")))')"
# The wheels' shared libraries: venv/lib, each package's bundled .libs, and the shim dir whose
# librmw_implementation.so is Fast DDS's (the wheels load the rmw by that name).
libs="$venv/lib/rmw-shim:$venv/lib"
for d in "$site"/ros_*.libs; do libs="$libs:$d"; done
export LD_LIBRARY_PATH="$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# The prebuilt rosbridge binary embeds Python for rclpy's type support and needs it loaded.
export LD_PRELOAD="$libpython${LD_PRELOAD:+:$LD_PRELOAD}"
export AMENT_PREFIX_PATH="$venv"
export PYTHONPATH="$site${PYTHONPATH:+:$PYTHONPATH}"
export PATH="$venv/bin:$PATH"
export ROS_DISTRO=jazzy
export RMW_IMPLEMENTATION=rmw_fastrtps_cpp
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
unset ros_dir venv site libpython libs d
