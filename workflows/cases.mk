# The shipped cases: share/cases/<case>.json, run on the assembly packed from
# share/specimens/<specimen>.json. One block per case:
#   CASES += <case>
#   <case>.specimen := <specimen>

CASES += demo-ucs
demo-ucs.specimen := demo
