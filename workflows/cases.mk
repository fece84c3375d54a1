# The shipped cases: share/cases/<case>.json, run on the assembly packed from
# share/specimens/<specimen>.json. One block per case:
#   CASES += <case>
#   <case>.specimen := <specimen>

CASES += demo-ucs
demo-ucs.specimen := demo

# Oñate et al. 2015, §10.1: cement, 1" x 2" cores, 42 000 spheres.
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
