#include "post/pvd.h"
#include "post/output.h"

void pvd_write(const char *path, const pvd_entry *e, size_t n)
{
	out_text o;
	out_text_open(&o, path);
	fputs("<?xml version=\"1.0\"?>\n"
	      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
	      "  <Collection>\n",
	      o.f);
	for (size_t k = 0; k < n; k++)
		fprintf(o.f, "    <DataSet timestep=\"%.10g\" part=\"%d\" file=\"%s\"/>\n", e[k].t,
		        e[k].part, e[k].file);
	fputs("  </Collection>\n</VTKFile>\n", o.f);
	out_text_commit(&o);
}
