"""The package's version: the project's (CMakeLists.txt project(VERSION),
checked by the test python_venv_install)."""

__version__ = "0.1.0"
