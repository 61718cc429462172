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


# Headers that never end, or whose one line never ends (issue 16, part 1):
# each reader stops after 1 MiB of header and names the file and the limit.
def endless(name, head, line):
    with open(replace(os.path.join(out, name)), "wb") as f:
        f.write(head)
        f.write(line * ((2 << 20) // len(line)))  # 2 MiB of header lines and no end


def endless_line(name, head):
    # 1 GB with no newline after `head`; sparse, so it costs no disk.
    with open(replace(os.path.join(out, name)), "wb") as f:
        f.write(head)
        f.truncate(1 << 30)


endless("endless.nrrd", b"NRRD0004\n", b"# no blank line ends this header\n")
scene("nrrd-endless-header", "endless.nrrd")
endless_line("long-line.nrrd", b"NRRD0004\ntype: ")
scene("nrrd-long-line", "long-line.nrrd")
endless("endless.mha", b"ObjectType = Image\nNDims = 3\n", b"Comment = no ElementDataFile ends this header\n")
scene("mha-endless-header", "endless.mha")
endless_line("long-line.mha", b"ObjectType = Image\nNDims = ")
scene("mha-long-line", "long-line.mha")

# Declared sizes far beyond the data (part 1): refused before anything that size is allocated.
mha = (b"ObjectType = Image\nNDims = 3\nDimSize = 1024 1024 1024\nElementSpacing = 0.1 0.1 0.1\n"
       b"ElementType = MET_FLOAT\n")
with open(replace(os.path.join(out, "huge.mha")), "wb") as f:
    f.write(mha + b"ElementDataFile = LOCAL\n" + bytes(1000))
scene("mha-huge-dims", "huge.mha")
packed = gzip.compress(bytes(1000))
with open(replace(os.path.join(out, "bomb.mha")), "wb") as f:
    f.write(mha + b"CompressedData = True\nCompressedDataSize = " + str(len(packed)).encode() +
            b"\nElementDataFile = LOCAL\n" + packed)
scene("mha-zlib-bomb", "bomb.mha")


def vti(name, compressor):
    with open(replace(os.path.join(out, name)), "w") as f:
        f.write(f"""<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian"{compressor}>
  <ImageData WholeExtent="0 1023 0 1023 0 1023" Origin="0 0 0" Spacing="0.1 0.1 0.1">
    <Piece Extent="0 1023 0 1023 0 1023">
      <PointData Scalars="density">
        <DataArray type="Float32" Name="density" format="ascii">0 0 0 0</DataArray>
      </PointData>
    </Piece>
  </ImageData>
</VTKFile>
""")


# VTK XML markup that never ends: a 2 MiB attribute (with a '>' in it) before any data.
with open(replace(os.path.join(out, "endless-markup.vti")), "w") as f:
    f.write('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="1.0" Note="> ' + "x" * (2 << 20) +
            '">\n</VTKFile>\n')
scene("vti-endless-markup", "endless-markup.vti")

vti("huge.vti", "")
scene("vti-huge-extent", "huge.vti")
vti("bomb.vti", ' compressor="vtkZLibDataCompressor"')
scene("vti-zlib-bomb", "bomb.vti")

# A CT slice whose Rows x Columns (30000 x 30000 x 16 bits, 1.8 GB) is far
# more than the 200 bytes of Pixel Data it holds. Built from pydicom's CT_small.dcm.
import pydicom  # noqa: E402  (Debian: python3-pydicom)
from pydicom.data import get_testdata_file  # noqa: E402

ds = pydicom.dcmread(get_testdata_file("CT_small.dcm"))
ds.Rows = 30000
ds.Columns = 30000
ds.PixelData = bytes(200)
ds.save_as(replace(os.path.join(out, "huge.dcm")))
scene("dcm-huge-rows", "huge.dcm")

# The same lie in a deflated data set (transfer syntax 1.2.840.10008.1.2.1.99):
# the structure check inflates it (bounded) and walks it like any other.
from pydicom.uid import DeflatedExplicitVRLittleEndian  # noqa: E402

ds.file_meta.TransferSyntaxUID = DeflatedExplicitVRLittleEndian
ds.is_little_endian = True
ds.is_implicit_VR = False
ds.save_as(replace(os.path.join(out, "huge-deflated.dcm")))
scene("dcm-deflated-huge-rows", "huge-deflated.dcm")

# A deflated data set that inflates without end (a "zip bomb" slice): the
# file meta information of huge-deflated.dcm, then 100 MB of zeros deflated.
import struct  # noqa: E402
import zlib  # noqa: E402
with open(os.path.join(out, "huge-deflated.dcm"), "rb") as f:
    deflated = f.read()
# (0002,0000) UL, explicit VR: tag, "UL", length 4, then the meta group's length.
meta_end = 132 + 12 + struct.unpack_from("<I", deflated, 132 + 8)[0]
packer = zlib.compressobj(9, zlib.DEFLATED, -15)
bomb = packer.compress(bytes(100 << 20)) + packer.flush()
with open(replace(os.path.join(out, "bomb.dcm")), "wb") as f:
    f.write(deflated[:meta_end] + bomb)
scene("dcm-deflate-bomb", "bomb.dcm")


# Trajectory urls that are a FIFO or /dev/zero: a clear error, not a hang.
def device_scene(name, url):
    with open(os.path.join(out, name + ".x3d"), "w") as f:
        f.write(f"""<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Immersive" version="3.3">
  <Scene>
    <VolumeObject url='"phantom:tooth?size=16,16,12"'/>
    <HandDevice url='"{url}"'><MillTool/><SurfacePointRenderer/></HandDevice>
  </Scene>
</X3D>
""")


os.mkfifo(replace(os.path.join(out, "fifo.csv")))
device_scene("trajectory-fifo", "fifo.csv")
os.symlink("/dev/zero", replace(os.path.join(out, "zero.csv")))
device_scene("trajectory-zero", "zero.csv")


# Not hostile, large: a 512³ CT-sized volume, all air but a 40³ cube. Read a
# slab at a time it fits a 400 MB address space; a dense float copy alone
# would take 512 MB (the readers made one until Dec 2026).
size, lo, hi = 512, 236, 276
row_air, row_cube = bytes(size), bytes(lo) + bytes([200]) * (hi - lo) + bytes(size - hi)
slice_air = row_air * size
slice_cube = row_air * lo + row_cube * (hi - lo) + row_air * (size - hi)
with open(replace(os.path.join(out, "sparse.nrrd")), "wb") as f:
    f.write(b"NRRD0004\ntype: uchar\ndimension: 3\nsizes: 512 512 512\nspacings: 0.1 0.1 0.1\nencoding: gzip\n\n")
    packer = zlib.compressobj(1, zlib.DEFLATED, 16 + 15)
    for k in range(size):
        f.write(packer.compress(slice_cube if lo <= k < hi else slice_air))
    f.write(packer.flush())
with open(os.path.join(out, "sparse-large.x3d"), "w") as f:
    f.write("""<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Immersive" version="3.3">
  <Scene>
    <VolumeObject url='"sparse.nrrd"' airValue="0" isoValue="100"/>
  </Scene>
</X3D>
""")
