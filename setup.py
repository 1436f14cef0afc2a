# catkin_python_setup() reads this (never run it by hand): the Python package tow_sim from python/, beside the
# messages and the compiled tow_sim._core that catkin and CMake put into the same package (docs/python.md).
from setuptools import setup

from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["tow_sim"], package_dir={"": "python"}))
