"""Builds the package with the message types lcm-gen generates from the
project's .lcm files (../lcmtypes), as python/CMakeLists.txt does for the
build tree and the Debian package. Metadata: pyproject.toml."""

import glob
import os
import shutil
import subprocess
import tempfile

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
LCM_DIR = os.path.join(HERE, "..", "lcmtypes")


class BuildWithLcmTypes(build_py):
    """build_py, then the generated <type>.py and the .lcm files (read for
    units) into the built package, unless the tree already holds them (the
    assembled build/python)."""

    def run(self):
        super().run()
        package_dir = os.path.join(self.build_lib, "birotor")
        if glob.glob(os.path.join(HERE, "birotor", "*_t.py")):
            return
        lcm_files = sorted(glob.glob(os.path.join(LCM_DIR, "*.lcm")))
        if not lcm_files:
            raise SystemExit(f"birotor: no .lcm files in {LCM_DIR} (install from the repository's python/ folder)")
        lcm_gen = shutil.which("lcm-gen")
        if lcm_gen is None:
            raise SystemExit("birotor: lcm-gen not found (Debian package liblcm-bin)")
        with tempfile.TemporaryDirectory() as generated:
            subprocess.run([lcm_gen, "--python", "--ppath", generated] + lcm_files, check=True)
            for module in glob.glob(os.path.join(generated, "birotor", "*_t.py")):
                shutil.copy(module, package_dir)
        os.makedirs(os.path.join(package_dir, "lcmtypes"), exist_ok=True)
        for lcm_file in lcm_files:
            shutil.copy(lcm_file, os.path.join(package_dir, "lcmtypes"))


setup(cmdclass={"build_py": BuildWithLcmTypes})
