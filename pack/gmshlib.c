/* Loading gmsh (see gmshlib.h). The library stays loaded: gmsh keeps
 * global state between gmshInitialize and gmshFinalize, and a process
 * builds one geometry. */
#include <dlfcn.h>
#include <string.h>

#include "lib/err.h"
#include "pack/gmshlib.h"

const gmsh_library *gmshlib_load(void)
{
	static gmsh_library lib;
	static int loaded;
	if (loaded)
		return &lib;
	void *h = dlopen(DEM_GMSH_SONAME, RTLD_LAZY | RTLD_LOCAL);
	if (!h) {
		err_set("cannot load the gmsh library: %s", dlerror());
		return NULL;
	}
	/* A function pointer from dlsym's object pointer, as POSIX allows. */
#define GMSH_LOOKUP(f)                                                                \
	{                                                                             \
		void *p = dlsym(h, #f);                                               \
		if (!p) {                                                             \
			err_set("the gmsh library %s lacks %s", DEM_GMSH_SONAME, #f); \
			return NULL;                                                  \
		}                                                                     \
		memcpy(&lib.f, &p, sizeof p);                                         \
	}
	GMSH_FUNCTIONS(GMSH_LOOKUP)
#undef GMSH_LOOKUP
	loaded = 1;
	return &lib;
}
