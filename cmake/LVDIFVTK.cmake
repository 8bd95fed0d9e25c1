# The VTK layer: modules found by their vtk.module files under Filters/, IO/
# and Rendering/, built with VTK's module system against Debian's VTK 9.1.
# (The ParaView plugin is a second build tree: see Apps/ParaViewPlugin.)
find_package(VTK 9.1 REQUIRED)
