# The hideseek Python package (python/hideseek); catkin_python_setup() installs it. Its C++ part,
# hideseek/_core, is built by CMakeLists.txt.
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=["hideseek"], package_dir={"": "python"}))
