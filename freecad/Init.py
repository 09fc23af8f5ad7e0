# FreeCAD runs this at start-up for the qmotion add-on (docs/freecad.md). The features need
# nothing registered: `import qmotion_freecad` in a macro or the console is enough.
