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
sys.exit(1 if failures or info.GetNumberOfPoints() == 0 or first_frame == 0 else 0)
