"""The package's version: the project's (CMakeLists.txt project(VERSION),
checked by the test python_package_version)."""

__version__ = "0.1.0"
