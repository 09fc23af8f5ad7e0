"""The workbench's commands (GUI only): each makes one feature from the selection."""
import os

import FreeCAD
import FreeCADGui

from . import features

ICONS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "icons")


def _selected():
    return FreeCADGui.Selection.getSelection()


def _motion(selection):
    for obj in selection:
        if "MotionFile" in obj.PropertiesList:
            return obj
    return None


class _Command:
    icon, menu, tip = "", "", ""

    def GetResources(self):
        return {"Pixmap": os.path.join(ICONS, self.icon), "MenuText": self.menu,
                "ToolTip": self.tip}

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        obj = self.make(doc, _selected())
        if obj is not None:
            doc.recompute()


class MotionCommand(_Command):
    icon, menu = "motion.svg", "Motion from placements"
    tip = ("A motion through the placements of the selected objects, in the order selected "
           "(edit Placements, Times, Scheme afterwards)")

    def make(self, doc, selection):
        if not selection:
            FreeCAD.Console.PrintError("qmotion: select two or more objects for their poses\n")
            return None
        return features.make_motion(doc, [o.Placement for o in selection])


class SweepCommand(_Command):
    icon, menu = "sweep.svg", "Sweep a profile"
    tip = "The exact sweep of the selected profile (a sketch, circle or wire) by the selected motion"

    def make(self, doc, selection):
        motion = _motion(selection)
        others = [o for o in selection if o is not motion]
        if motion is None or not others:
            FreeCAD.Console.PrintError("qmotion: select a motion and a profile\n")
            return None
        return features.make_sweep(doc, motion, others[0])


class TrajectoryCommand(_Command):
    icon, menu = "trajectory.svg", "Trajectory of a point"
    tip = "The exact trajectory of the moving origin under the selected motion (edit Point)"

    def make(self, doc, selection):
        motion = _motion(selection)
        if motion is None:
            FreeCAD.Console.PrintError("qmotion: select a motion\n")
            return None
        return features.make_trajectory(doc, motion, (0, 0, 0))


class SweptVolumeCommand(_Command):
    icon, menu = "volume.svg", "Swept volume"
    tip = ("The certified swept volume of the selected solid (or a 6 mm ball cutter) under the "
           "selected motion")

    def make(self, doc, selection):
        motion = _motion(selection)
        others = [o for o in selection if o is not motion]
        if motion is None:
            FreeCAD.Console.PrintError("qmotion: select a motion (and a solid)\n")
            return None
        return features.make_swept_volume(doc, motion,
                                          others[0] if others else "cutter:ball,6,20")


COMMANDS = {"QMotion_Motion": MotionCommand, "QMotion_Sweep": SweepCommand,
            "QMotion_Trajectory": TrajectoryCommand, "QMotion_SweptVolume": SweptVolumeCommand}


def register():
    for name, cls in COMMANDS.items():
        FreeCADGui.addCommand(name, cls())
    return list(COMMANDS)
