#!/usr/bin/python3
"""Writes the hostile-input corpus into OUT (FIFOs, device links and forged
headers cannot live in git): one scene per case, each loading one bad volume.

  make-hostile.py OUT
"""
import gzip
import os
import sys

out = sys.argv[1]
os.makedirs(out, exist_ok=True)


def scene(name, url):
    with open(os.path.join(out, name + ".x3d"), "w") as f:
        f.write(f"""<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Immersive" version="3.3">
  <Scene>
    <VolumeObject url='"{url}"'/>
  </Scene>
</X3D>
""")


def replace(path):
    if os.path.lexists(path):
        os.remove(path)
    return path


# A named pipe: opening it for reading waits for a writer that never comes.
os.mkfifo(replace(os.path.join(out, "fifo.nrrd")))
scene("fifo", "fifo.nrrd")

# Volume names that are /dev/zero: reading never ends.
for ext in ("nrrd", "mha", "dcm"):
    os.symlink("/dev/zero", replace(os.path.join(out, "zero." + ext)))
    scene("zero-" + ext, "zero." + ext)

# A 1 KB gzip NRRD whose header claims 1024³ voxels (4 GiB of floats once read).
with open(replace(os.path.join(out, "bomb.nrrd")), "wb") as f:
    f.write(b"NRRD0004\ntype: uchar\ndimension: 3\nsizes: 1024 1024 1024\nspacings: 0.1 0.1 0.1\nencoding: gzip\n\n")
    f.write(gzip.compress(bytes(1000)))
scene("gzip-bomb", "bomb.nrrd")
