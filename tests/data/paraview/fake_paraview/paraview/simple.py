# The part of paraview.simple that data/paraview/open_run.py calls, re-done on VTK's own readers
# (python3-vtk9, which Debian's libvtk9-dev pulls in), so the script is checked where ParaView
# cannot be installed. It is strict where ParaView would only show something wrong:
# - OpenDataFile reads a .pvd collection and every file it lists with VTK's XML readers (a
#   missing or unreadable file is an error, not an empty block);
# - ColorBy needs the array, with that association (POINTS or CELLS), in every non-empty block
#   of every time step: colouring by an array some steps lack is an error;
# - Slice cuts the input with vtkCutter at every time step and must produce polygons;
# - displays, colour maps and slices accept only the properties the script may set, and presets
#   only by names ParaView ships.
# What happened is kept in RECORD for tests/data/paraview/check_open_run.py.
import os
import xml.etree.ElementTree as ElementTree

from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkPlane
from vtkmodules.vtkFiltersCore import vtkCutter
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader

RECORD = {"sources": [], "displays": [], "luts": {}, "screenshots": []}
PRESETS = ("Cool to Warm", "Viridis (matplotlib)", "Inferno (matplotlib)", "Jet", "Rainbow Uniform")
READERS = {".vtp": vtkXMLPolyDataReader, ".vti": vtkXMLImageDataReader}


def read_vtk_xml(path):
    if not os.path.isfile(path):
        raise FileNotFoundError("listed in a .pvd but missing: " + path)
    reader = READERS[os.path.splitext(path)[1]]()
    errors = []
    reader.AddObserver(vtkCommand.ErrorEvent, lambda *args: errors.append(path))
    reader.SetFileName(path)
    reader.Update()
    if errors or reader.GetErrorCode() != 0:
        raise IOError("VTK cannot read " + path)
    return reader.GetOutput()


class ArrayInfo:
    def __init__(self, name, arrays):
        self.Name = name
        self._arrays = arrays

    def GetRange(self, component=0):
        ranges = [a.GetRange(component) for a in self._arrays]
        return (min(r[0] for r in ranges), max(r[1] for r in ranges))


class FieldInfo:
    """Arrays of one association over the blocks of the current time step (as ParaView lists
    them: an array any block has)."""

    def __init__(self, blocks, association):
        self._blocks = blocks
        self._association = association
        self._names = []
        for b in blocks:
            data = field_data(b, association)
            for i in range(data.GetNumberOfArrays()):
                if data.GetArrayName(i) not in self._names:
                    self._names.append(data.GetArrayName(i))

    def GetNumberOfArrays(self):
        return len(self._names)

    def GetArray(self, i):
        return self[self._names[i]]

    def keys(self):
        return list(self._names)

    def __getitem__(self, name):
        arrays = [field_data(b, self._association).GetArray(name) for b in self._blocks]
        return ArrayInfo(name, [a for a in arrays if a is not None])


def field_data(block, association):
    return block.GetPointData() if association == "POINTS" else block.GetCellData()


class DataInfo:
    def __init__(self, blocks):
        self._blocks = blocks

    def GetBounds(self):
        bounds = [b.GetBounds() for b in self._blocks if b.GetNumberOfPoints() > 0]
        low = [min(b[2 * a] for b in bounds) for a in range(3)]
        high = [max(b[2 * a + 1] for b in bounds) for a in range(3)]
        return [low[0], high[0], low[1], high[1], low[2], high[2]]


class Source:
    """A time series: {time: [blocks]}; the current time as UpdatePipeline set it."""

    def __init__(self, steps, name):
        self._steps = steps
        self.name = name
        self._time = min(steps) if steps else None
        RECORD["sources"].append(self)

    @property
    def TimestepValues(self):
        return sorted(self._steps)

    def set_time(self, t):
        if t is None or not self._steps:
            return
        # ParaView's PVD reader shows the last step at or before t (the first before them all).
        earlier = [s for s in self._steps if s <= t]
        self._time = max(earlier) if earlier else min(self._steps)

    def blocks(self, t=None):
        return self._steps.get(self._time if t is None else t, [])

    def all_steps(self):
        return sorted(self._steps.items())

    @property
    def PointData(self):
        return FieldInfo(self.blocks(), "POINTS")

    @property
    def CellData(self):
        return FieldInfo(self.blocks(), "CELLS")

    def GetDataInformation(self):
        return DataInfo(self.blocks())


class Strict:
    """Accepts only the attributes named in ALLOWED (a typo would be a silent no-op in ParaView)."""

    ALLOWED = ()

    def __setattr__(self, name, value):
        if not name.startswith("_") and name not in self.ALLOWED:
            raise AttributeError("%s has no property %s here" % (type(self).__name__, name))
        object.__setattr__(self, name, value)


class Plane(Strict):
    ALLOWED = ("Origin", "Normal")

    def __init__(self):
        self.Origin = [0.0, 0.0, 0.0]
        self.Normal = [1.0, 0.0, 0.0]


class SliceFilter(Source):
    def __init__(self, source):
        self._input = source
        self.SliceType = Plane()
        self._steps = {}
        self._time = source._time
        self.name = "Slice(%s)" % source.name
        RECORD["sources"].append(self)

    def blocks(self, t=None):
        plane = vtkPlane()
        plane.SetOrigin(*self.SliceType.Origin)
        plane.SetNormal(*self.SliceType.Normal)
        out = []
        for block in self._input.blocks(self._time if t is None else t):
            cutter = vtkCutter()
            cutter.SetCutFunction(plane)
            cutter.SetInputData(block)
            cutter.Update()
            out.append(cutter.GetOutput())
        return out

    def all_steps(self):
        return [(t, self.blocks(t)) for t, _ in self._input.all_steps()]

    @property
    def TimestepValues(self):
        return self._input.TimestepValues


class Display(Strict):
    ALLOWED = ("DiffuseColor", "Opacity", "ColorArrayName")

    def __setattr__(self, name, value):
        if name == "ColorArrayName":  # [association, name]; name "" = no array (a solid colour)
            association, array = value
            if association not in ("POINTS", "CELLS"):
                raise ValueError("association " + association)
            if array == "":
                object.__setattr__(self, "_colour", None)
            else:
                ColorBy(self, (association, array))
            return
        Strict.__setattr__(self, name, value)

    def __init__(self, source, view):
        self._source = source
        self._view = view
        self._colour = "default"
        self._scalar_bar = False
        RECORD["displays"].append(self)

    def SetScalarBarVisibility(self, view, visible):
        if view is not self._view:
            raise ValueError("scalar bar for another view")
        if visible and self._colour in (None, "default"):
            raise ValueError("a scalar bar on a display not coloured by an array")
        self._scalar_bar = visible


class Lut(Strict):
    ALLOWED = ()

    def __init__(self, name):
        self._name = name
        self._preset = None
        self._range = None

    def ApplyPreset(self, name, rescale):
        if name not in PRESETS:
            raise ValueError("no ParaView preset named " + name)
        self._preset = name

    def RescaleTransferFunction(self, low, high):
        if not low < high:
            raise ValueError("empty colour range %r..%r" % (low, high))
        self._range = (low, high)


class View:
    pass


class AnimationScene(Strict):
    ALLOWED = ("AnimationTime",)

    def UpdateAnimationUsingDataTimeSteps(self):
        pass


_VIEW = View()
_SCENE = AnimationScene()


def GetActiveViewOrCreate(kind):
    if kind != "RenderView":
        raise ValueError("unexpected view " + kind)
    return _VIEW


def GetAnimationScene():
    return _SCENE


def OpenDataFile(path):
    if not path.endswith(".pvd"):
        raise ValueError("this stand-in opens .pvd collections only: " + path)
    root = ElementTree.parse(path).getroot()
    steps = {}
    for ds in root.iter("DataSet"):
        block = read_vtk_xml(os.path.join(os.path.dirname(path), ds.get("file")))
        steps.setdefault(float(ds.get("timestep", "0")), []).append(block)
    if not steps:
        raise ValueError("no data sets in " + path)
    return Source(steps, os.path.basename(path))


def UpdatePipeline(time=None, proxy=None):
    proxy.set_time(time)


def Slice(Input):
    return SliceFilter(Input)


def Show(source, view):
    return Display(source, view)


def ColorBy(display, value):
    if value is None:
        # ParaView 5.11 (Debian 12) takes the association of the display's current colour array,
        # and fails with "invalid association string 'NONE'" when it has none yet (seen in the
        # real ParaView, data/paraview/check_in_debian.sh): set ColorArrayName = [assoc, ""].
        raise ValueError("ColorBy(display, None) fails in ParaView 5.11 on an uncoloured display")
    association, name = value
    if association not in ("POINTS", "CELLS"):
        raise ValueError("association " + association)
    non_empty = 0
    for t, blocks in display._source.all_steps():
        for block in blocks:
            if block.GetNumberOfCells() == 0:
                continue  # nothing to colour (no surface left, or an empty cut)
            non_empty += 1
            if field_data(block, association).GetArray(name) is None:
                raise KeyError("%s: no %s array %s at t = %g" % (display._source.name, association,
                                                                 name, t))
    if non_empty == 0:
        raise ValueError("%s coloured by %s but nothing to show" % (display._source.name, name))
    display._colour = value


def GetColorTransferFunction(name):
    return RECORD["luts"].setdefault(name, Lut(name))


class ScalarBar(Strict):
    ALLOWED = ("Title", "ComponentTitle")


def GetScalarBar(lut, view):
    if not isinstance(lut, Lut):
        raise TypeError("GetScalarBar takes a colour map")
    return ScalarBar()


def ResetCamera(view):
    pass


def SaveScreenshot(path, view, ImageResolution=None):
    RECORD["screenshots"].append((path, ImageResolution))
