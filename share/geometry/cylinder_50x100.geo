// UCS/triaxial specimen, 50 mm x 100 mm (Onate et al. 2015, concrete and
// the reference case of pack's density figures). Lengths in metres; the
// axis is z, the base centred on the origin.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -0.05, 0, 0, 0.1, 0.025};
