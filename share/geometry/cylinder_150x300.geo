// Standard concrete cylinder, 150 mm x 300 mm (EN 12390 / ASTM C39).
// Lengths in metres; axis z, centred on the origin.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -0.15, 0, 0, 0.3, 0.075};
