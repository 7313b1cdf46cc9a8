"""`cmake --install` puts a package that imports and works from the install prefix alone."""

import os
import subprocess
import sys
import tempfile
import unittest

from support import ARM_SCENE

BUILD_DIR = os.environ.get("OCTOMOTION_BUILD_DIR", "")
INSTALL_DIR = os.environ.get("OCTOMOTION_PYTHON_INSTALL_DIR", "")
CMAKE = os.environ.get("CMAKE_COMMAND", "cmake")


@unittest.skipUnless(BUILD_DIR and INSTALL_DIR, "run by ctest (OCTOMOTION_BUILD_DIR)")
class InstallTest(unittest.TestCase):
    def test_installed_package_imports(self):
        with tempfile.TemporaryDirectory() as prefix:
            subprocess.run([CMAKE, "--install", BUILD_DIR, "--prefix", prefix,
                            "--component", "python"], check=True, capture_output=True)
            site = os.path.join(prefix, INSTALL_DIR)
            for f in ("__init__.py", "__init__.pyi", "py.typed"):
                self.assertTrue(os.path.exists(os.path.join(site, "octomotion", f)), f)
            script = (
                "import numpy, octomotion, sys\n"
                "assert octomotion.__file__.startswith(sys.argv[1]), octomotion.__file__\n"
                "s = octomotion.load_scene(sys.argv[2], resolution=0.04)\n"
                "print(len(s.check_many(numpy.zeros((3, s.dof)))))\n"
            )
            env = dict(os.environ, PYTHONPATH=site)
            out = subprocess.run([sys.executable, "-c", script, site, ARM_SCENE], env=env,
                                 cwd=prefix, check=True, capture_output=True, text=True)
            self.assertEqual(out.stdout.strip(), "3")


if __name__ == "__main__":
    unittest.main()
