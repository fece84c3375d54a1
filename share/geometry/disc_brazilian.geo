// Brazilian (indirect tension) disc, 1.487 inch diameter x 0.863 inch
// thickness (37.77 mm x 21.92 mm; Onate et al. 2015). Lengths in metres;
// the disc axis is z, the load is applied along a diameter.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -0.0109601, 0, 0, 0.0219202, 0.01888490};
