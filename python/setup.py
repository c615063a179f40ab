"""pip install ./python (offline, with Debian's python3-cffi, python3-numpy,
python3-setuptools): builds the cffi extension against libjumpcyl, found as
jumpcyl_build.py says (JUMPCYL_BUILD_DIR, pkg-config jumpcyl, or ../build)."""
from setuptools import setup

setup(
    name="jumpcyl",
    version="0.1.0",
    description="Where an off-centre-mass cylinder rolling on an incline jumps: Python bindings of libjumpcyl",
    packages=["jumpcyl"],
    python_requires=">=3.9",
    install_requires=["cffi>=1.15", "numpy"],
    extras_require={"pandas": ["pandas"], "plots": ["matplotlib"]},
    cffi_modules=["jumpcyl_build.py:ffibuilder"],
    zip_safe=False,
)
