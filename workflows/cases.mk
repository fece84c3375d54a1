# The shipped cases: share/cases/<case>.json, run on the assembly packed from
# share/specimens/<specimen>.json. One block per case:
#   CASES += <case>
#   <case>.specimen := <specimen>

CASES += demo-ucs
demo-ucs.specimen := demo

# Oñate et al. 2015, §10.1: cement, 1" x 2" cores (42 000 spheres; the USC
# test 16 000), the Brazilian disc 1.487" x 0.863" (16 000).
CASES += cement-ucs
cement-ucs.specimen := cement-1x2in

CASES += cement-triaxial-500psi
cement-triaxial-500psi.specimen := cement-1x2in

CASES += cement-triaxial-1000psi
cement-triaxial-1000psi.specimen := cement-1x2in

CASES += cement-triaxial-2000psi
cement-triaxial-2000psi.specimen := cement-1x2in

CASES += cement-triaxial-4000psi
cement-triaxial-4000psi.specimen := cement-1x2in

CASES += cement-usc
cement-usc.specimen := cement-1x2in-16k

CASES += cement-bts
cement-bts.specimen := cement-disc

CASES += cement-hydrostatic
cement-hydrostatic.specimen := cement-1x2in-16k

# §10.2: concrete, 150 x 300 mm cylinders (13 000 spheres; the 40 MPa test
# with unload-reload cycles 4 000), the Brazilian test on the split
# cylinder (27 000).
CASES += concrete-ucs
concrete-ucs.specimen := concrete-150x300

CASES += concrete-triaxial-4.5MPa
concrete-triaxial-4.5MPa.specimen := concrete-150x300

CASES += concrete-triaxial-9MPa
concrete-triaxial-9MPa.specimen := concrete-150x300

CASES += concrete-triaxial-40MPa
concrete-triaxial-40MPa.specimen := concrete-150x300-4k

CASES += concrete-triaxial-60MPa
concrete-triaxial-60MPa.specimen := concrete-150x300

CASES += concrete-bts
concrete-bts.specimen := split-cylinder-150x300

# §10.3: shale, 150 x 300 mm (UCS 37 000 spheres, BTS 27 000).
CASES += shale-ucs
shale-ucs.specimen := shale-150x300

CASES += shale-bts
shale-bts.specimen := split-cylinder-150x300

# seeds/002 §4.4: JCFPM concrete, 50 x 100 mm, monodisperse r = 1.25 mm, on
# the thesis' kind of specimen: Yade's randomDensePack (11 576 spheres,
# solid fraction 0.48; tools/yade-pack), taken as listed whatever COUNT says.
# The -dense run is the same case on pack's own, denser assembly.
CASES += jcfpm-concrete-ucs
jcfpm-concrete-ucs.specimen := jcfpm-50x100-yade
jcfpm-concrete-ucs.count := 0

CASES += jcfpm-concrete-ucs-dense
jcfpm-concrete-ucs-dense.specimen := jcfpm-50x100
jcfpm-concrete-ucs-dense.case := jcfpm-concrete-ucs

# The same material in a Brazilian test between platens (no source value:
# the Brazilian test of tools/compare-yade, validation.md section 8).
CASES += jcfpm-concrete-bts
jcfpm-concrete-bts.specimen := jcfpm-disc-50x25
