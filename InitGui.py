# LeatherCut workbench: GUI registration (FreeCAD runs this file with exec and
# injects FreeCAD, FreeCADGui, Gui and Workbench).  Names defined here are not
# visible inside class bodies, so everything the class needs is imported in
# its methods.


class LeatherCutWB(Workbench):  # noqa: F821 - injected by FreeCAD
    """DXF pattern -> recognised parts -> nesting -> cut path -> machine."""

    MenuText = "LeatherCut"
    ToolTip = "Prepare leather and flame cutting jobs: DXF import, contour recognition, " \
              "nesting, cut path planning, post-processing and sending to the cutter"

    def __init__(self):
        from LeatherCutWorkbench.commands import paths
        self.__class__.Icon = paths.icon("LeatherCut")

    def Initialize(self):
        import FreeCADGui
        from LeatherCutWorkbench import commands
        from LeatherCutWorkbench.commands import paths

        FreeCADGui.addLanguagePath(paths.TRANSLATIONS_DIR)
        FreeCADGui.updateLocale()
        FreeCADGui.addIconPath(paths.ICON_DIR)
        names = commands.register_all()
        self.appendToolbar("LeatherCut", names)
        self.appendMenu("&LeatherCut", names)
        FreeCADGui.addPreferencePage(paths.ui("Preferences"), "LeatherCut")

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def ContextMenu(self, recipient):
        from LeatherCutWorkbench import commands
        self.appendContextMenu("LeatherCut", commands.context_commands())

    def GetClassName(self):
        return "Gui::PythonWorkbench"


Gui.addWorkbench(LeatherCutWB())  # noqa: F821 - injected by FreeCAD
