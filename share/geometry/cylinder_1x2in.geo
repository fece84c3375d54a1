// Rock core specimen, 1 inch x 2 inches (25.4 mm x 50.8 mm; shale UCS and
// triaxial tests in Onate et al. 2015). Lengths in metres; axis z.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -0.0254, 0, 0, 0.0508, 0.0127};
