"""Run by check_paraview.sh with pvpython: opens DIR/result.xdmf with OpenDataFile (the reader ParaView
picks by itself), prints the first frame's point count with and without a time, reads the last frame and
compares its points and fields with the HDF5 datasets."""
import sys

import h5py
import numpy as np
from paraview import servermanager
from paraview.simple import OpenDataFile, UpdatePipeline
from vtkmodules.numpy_interface import dataset_adapter as dsa

directory = sys.argv[1]
reader = OpenDataFile(f"{directory}/result.xdmf")
if reader is None:
    sys.exit("ParaView found no reader for result.xdmf")
times = list(reader.TimestepValues) if reader.TimestepValues else []
print(f"ParaView {servermanager.vtkSMProxyManager.GetParaViewSourceVersion()}, reader {reader.GetXMLName()}, {len(times)} time steps")
# Without a time the pipeline asks for no UPDATE_TIME_STEP; Xdmf3ReaderS then reads every frame of the
# temporal collection and cannot fit them into the one unstructured grid it announced (docs/results.md,
# "The XDMF sidecars"). The proxy's UpdatePipeline(t) asks for t; paraview.simple.UpdatePipeline(time=0.0)
# does not (it tests `if time:`), so the first frame is asked for through the proxy.
reader.UpdatePipeline()
without_time = reader.GetDataInformation().GetNumberOfPoints()
reader.UpdatePipeline(times[0] if times else 0.0)
first_frame = reader.GetDataInformation().GetNumberOfPoints()
print(f"first frame: {without_time} points without a time (UpdatePipeline()), "
      f"{first_frame} at t = {times[0] if times else 0.0} (reader.UpdatePipeline({times[0] if times else 0.0}))")
UpdatePipeline(time=times[-1] if times else 0, proxy=reader)
info = reader.GetDataInformation()
print(f"last frame t = {times[-1] if times else None}: {info.GetNumberOfPoints()} points, {info.GetNumberOfCells()} cells")

data = servermanager.Fetch(reader)
if data.IsA("vtkMultiBlockDataSet") or data.IsA("vtkPartitionedDataSetCollection"):
    data = dsa.WrapDataObject(data)
    points = np.vstack(list(data.Points.Arrays))
    point_data = {name: np.concatenate(list(data.PointData[name].Arrays)) for name in data.PointData.keys()}
    cell_data = {name: np.concatenate(list(data.CellData[name].Arrays)) for name in data.CellData.keys()}
else:
    data = dsa.WrapDataObject(data)
    points = np.asarray(data.Points)
    point_data = {name: np.asarray(data.PointData[name]) for name in data.PointData.keys()}
    cell_data = {name: np.asarray(data.CellData[name]) for name in data.CellData.keys()}

h5 = h5py.File(f"{directory}/result.h5", "r")
k = len(h5["/frames/time"]) - 1
failures = 0


def compare(what, got, expected):
    global failures
    got, expected = np.asarray(got, dtype=float), np.asarray(expected, dtype=float)
    ok = got.shape == expected.shape and np.array_equal(got, expected)
    failures += not ok
    print(f"  {what}: {got.shape}, range [{got.min():.6g}, {got.max():.6g}] {'= HDF5' if ok else '!= HDF5 ' + str(expected.shape)}")


compare("points", points, h5[f"/frames/{k}/position"][()])
for name in sorted(point_data):
    source = h5[f"/frames/{k}/{name}"] if name in h5[f"/frames/{k}"] else h5["/mesh/nodes"]
    compare(f"point data {name}", point_data[name], source[()])
for name in sorted(cell_data):
    if name in h5[f"/frames/{k}"]:
        expected = h5[f"/frames/{k}/{name}"][()]
        if name == "cauchy_stress" and cell_data[name].shape[-1] == 9:  # Tensor6 expanded to 3 × 3
            xx, xy, xz, yy, yz, zz = expected.T
            expected = np.stack([xx, xy, xz, xy, yy, yz, xz, yz, zz], axis=1)
        compare(f"cell data {name}", cell_data[name], expected)
    elif name == "body":
        compare("cell data body", cell_data[name], h5["/mesh/body"][()])
# The other reader the README names: the temporal Xdmf3 reader, by name.
from paraview import simple  # noqa: E402

other = simple.Xdmf3ReaderT(FileName=[f"{directory}/result.xdmf"])
simple.UpdatePipeline(time=times[-1] if times else 0, proxy=other)
other_points = other.GetDataInformation().GetNumberOfPoints()
print(f"Xdmf3ReaderT: {len(other.TimestepValues)} time steps, {other_points} points at the last one")
failures += other_points != info.GetNumberOfPoints()

# Other layouts of the same frames, each opened with OpenDataFile and read without a time: why result.xdmf
# keeps its layout (docs/results.md, "The XDMF sidecars"). Without a time Xdmf3ReaderS reads every grid in
# the file, so only a file that holds one frame loads that frame; the others load 0 points or all frames.
import os  # noqa: E402
import re  # noqa: E402
import shutil  # noqa: E402
import tempfile  # noqa: E402

written = open(f"{directory}/result.xdmf").read()
head, rest = written.split('    <Grid Name="frames" GridType="Collection" CollectionType="Temporal">\n', 1)
frames = re.findall(r"      <Grid Name=\"frame_\d+\" GridType=\"Uniform\">.*?\n      </Grid>\n", rest, re.S)
tail = "  </Domain>\n</Xdmf>\n"


def temporal(grids):
    return '    <Grid Name="frames" GridType="Collection" CollectionType="Temporal">\n' + "".join(grids) + "    </Grid>\n"


def spatial(frame):  # the frame's time on a spatial collection around it
    time = re.search(r"<Time Value=\"[^\"]*\"/>", frame).group(0)
    return ('      <Grid Name="step" GridType="Collection" CollectionType="Spatial">\n        ' + time + "\n" +
            frame.replace(time, "") + "      </Grid>\n")


mesh = re.sub(r"<Time Value=\"[^\"]*\"/>", "", frames[0]).replace('Name="frame_0"', 'Name="mesh"')
layouts = [
    ("as written: a temporal collection of the frames", head + temporal(frames) + tail),
    ("each frame a spatial collection carrying the time", head + temporal(spatial(f) for f in frames) + tail),
    ("a mesh grid beside the temporal collection (meshio's TimeSeriesWriter)", head + mesh + temporal(frames) + tail),
    ("the first frame alone", head + frames[0] + tail),
]
scratch = tempfile.mkdtemp()
os.symlink(os.path.abspath(f"{directory}/result.h5"), f"{scratch}/result.h5")
n_points = first_frame
print(f"layouts read without a time ({len(frames)} frames of {n_points} points each):")
for k, (what, text) in enumerate(layouts):
    path = f"{scratch}/layout_{k}.xdmf"
    open(path, "w").write(text)
    candidate = OpenDataFile(path)
    values = candidate.TimestepValues
    steps = len(values) if hasattr(values, "__len__") else int(values is not None)
    candidate.UpdatePipeline()
    got = candidate.GetDataInformation()
    print(f"  {what}: {candidate.GetXMLName()}, {steps} time steps, {got.GetNumberOfPoints()} points "
          f"({got.GetDataSetTypeAsString()})")
shutil.rmtree(scratch)
sys.exit(1 if failures or info.GetNumberOfPoints() == 0 or first_frame == 0 else 0)
