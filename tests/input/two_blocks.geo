// Two blocks meshed with hexahedra for tests/input/gmsh_groups.py:
// an anvil (physical volume "Anvil", base "Base") and, 5 mm above it, a
// striker (physical volume "Striker", top face physical surface 7, unnamed).
// Lengths in m; 2 x 2 elements across, 8 along z.
Point(1) = {0, 0, 0, 1};
Point(2) = {0.02, 0, 0, 1};
Line(1) = {1, 2};
Transfinite Curve{1} = 3;
base[] = Extrude{0, 0.02, 0}{ Curve{1}; Layers{2}; Recombine; };
anvil[] = Extrude{0, 0, 0.01}{ Surface{base[1]}; Layers{8}; Recombine; };

Point(11) = {0, 0, 0.015, 1};
Point(12) = {0.02, 0, 0.015, 1};
Line(11) = {11, 12};
Transfinite Curve{11} = 3;
bottom[] = Extrude{0, 0.02, 0}{ Curve{11}; Layers{2}; Recombine; };
striker[] = Extrude{0, 0, 0.01}{ Surface{bottom[1]}; Layers{8}; Recombine; };

Physical Volume("Anvil") = {anvil[1]};
Physical Surface("Base") = {base[1]};
Physical Volume("Striker") = {striker[1]};
Physical Surface(7) = {striker[0]};
