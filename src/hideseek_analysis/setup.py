# The hideseek_analysis Python package (python/hideseek_analysis); catkin_python_setup() installs it.
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=["hideseek_analysis"], package_dir={"": "python"}))
