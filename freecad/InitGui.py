# The qmotion workbench (docs/freecad.md): a toolbar and menu whose commands make qmotion's
# parametric features from the selection. FreeCAD runs this file at GUI start-up.
import os

import FreeCADGui


class QMotionWorkbench(FreeCADGui.Workbench):
    MenuText = "qmotion"
    ToolTip = "Exact rational motions: sweeps, trajectories and certified swept volumes"

    def __init__(self):
        import qmotion_freecad
        icons = os.path.join(os.path.dirname(qmotion_freecad.__file__), "icons")
        self.__class__.Icon = os.path.join(icons, "motion.svg")

    def Initialize(self):
        from qmotion_freecad import commands
        names = commands.register()
        self.appendToolbar("qmotion", names)
        self.appendMenu("qmotion", names)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(QMotionWorkbench())
