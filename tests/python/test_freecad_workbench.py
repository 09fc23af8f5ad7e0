"""The FreeCAD add-on's workbench wiring (freecad/InitGui.py, qmotion_freecad/commands.py),
loaded with stand-ins for FreeCAD's modules, since CI runs no GUI: the workbench registers,
its four commands are added with icons that exist, and a command with nothing selected
says so instead of failing. The features themselves run in real FreeCAD
(interop.freecad_features)."""
import os
import sys
import types

import pytest

ADDON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "freecad")


@pytest.fixture
def freecad_gui(monkeypatch):
    added = {"commands": {}, "workbenches": [], "errors": []}

    class Workbench:
        def appendToolbar(self, name, cmds):
            added["toolbar"] = (name, cmds)

        def appendMenu(self, name, cmds):
            added["menu"] = (name, cmds)

    console = types.SimpleNamespace(PrintError=added["errors"].append)
    fc = types.ModuleType("FreeCAD")
    fc.GuiUp, fc.ActiveDocument, fc.Console = True, object(), console
    gui = types.ModuleType("FreeCADGui")
    gui.Workbench = Workbench
    gui.addWorkbench = added["workbenches"].append
    gui.addCommand = lambda name, cmd: added["commands"].__setitem__(name, cmd)
    gui.Selection = types.SimpleNamespace(getSelection=lambda: [])
    for name, module in (("FreeCAD", fc), ("FreeCADGui", gui), ("Part", types.ModuleType("Part"))):
        monkeypatch.setitem(sys.modules, name, module)
    monkeypatch.syspath_prepend(ADDON)
    for name in [m for m in sys.modules if m.startswith("qmotion_freecad")]:
        monkeypatch.delitem(sys.modules, name)
    return added


def test_the_workbench_registers_four_commands_with_their_icons(freecad_gui):
    source = open(os.path.join(ADDON, "InitGui.py")).read()
    exec(compile(source, "InitGui.py", "exec"), {"__name__": "InitGui"})
    (wb,) = freecad_gui["workbenches"]
    assert wb.MenuText == "qmotion" and os.path.exists(wb.Icon)
    wb.Initialize()
    names = ["QMotion_Motion", "QMotion_Sweep", "QMotion_Trajectory", "QMotion_SweptVolume"]
    assert sorted(freecad_gui["commands"]) == sorted(names)
    assert freecad_gui["toolbar"] == ("qmotion", names) == freecad_gui["menu"]
    for name, cmd in freecad_gui["commands"].items():
        r = cmd.GetResources()
        assert os.path.exists(r["Pixmap"]) and r["MenuText"] and r["ToolTip"], name
        assert cmd.IsActive()
        cmd.Activated()  # nothing selected: an error on FreeCAD's console, no exception
    assert len(freecad_gui["errors"]) == 4 and all("select" in e for e in freecad_gui["errors"])
