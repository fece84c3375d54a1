// VTK readers behind tests/post/vtkread.h.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "tests/post/vtkread.h"

struct vtkr {
	vtkSmartPointer<vtkDataSet> data;
};

extern "C" vtkr *vtkr_open(const char *path)
{
	std::string p(path);
	vtkObject::GlobalWarningDisplayOff();
	vtkSmartPointer<vtkDataSet> data;
	if (p.size() > 4 && p.compare(p.size() - 4, 4, ".vtu") == 0) {
		vtkNew<vtkXMLUnstructuredGridReader> rd;
		if (!rd->CanReadFile(path))
			return nullptr;
		rd->SetFileName(path);
		rd->Update();
		data = rd->GetOutput();
	} else {
		vtkNew<vtkXMLPolyDataReader> rd;
		if (!rd->CanReadFile(path))
			return nullptr;
		rd->SetFileName(path);
		rd->Update();
		data = rd->GetOutput();
	}
	if (!data)
		return nullptr;
	return new vtkr{data};
}

extern "C" void vtkr_close(vtkr *r) { delete r; }
extern "C" long vtkr_npoints(const vtkr *r) { return (long)r->data->GetNumberOfPoints(); }
extern "C" long vtkr_ncells(const vtkr *r) { return (long)r->data->GetNumberOfCells(); }
extern "C" void vtkr_point(const vtkr *r, long k, double x[3]) { r->data->GetPoint(k, x); }
extern "C" int vtkr_cell_type(const vtkr *r, long c) { return r->data->GetCellType(c); }

extern "C" int vtkr_cell_size(const vtkr *r, long c)
{
	vtkNew<vtkIdList> ids;
	r->data->GetCellPoints(c, ids);
	return (int)ids->GetNumberOfIds();
}

extern "C" long vtkr_cell_point(const vtkr *r, long c, int k)
{
	vtkNew<vtkIdList> ids;
	r->data->GetCellPoints(c, ids);
	return (long)ids->GetId(k);
}

static vtkDataArray *find(const vtkr *r, char where, const char *name)
{
	vtkFieldData *fd = where == 'p'   ? static_cast<vtkFieldData *>(r->data->GetPointData())
	                   : where == 'c' ? static_cast<vtkFieldData *>(r->data->GetCellData())
	                                  : r->data->GetFieldData();
	return fd->GetArray(name);
}

extern "C" int vtkr_array(const vtkr *r, char where, const char *name, long *ntuples)
{
	vtkDataArray *a = find(r, where, name);
	if (!a)
		return -1;
	*ntuples = (long)a->GetNumberOfTuples();
	return a->GetNumberOfComponents();
}

extern "C" double vtkr_value(const vtkr *r, char where, const char *name, long tuple, int comp)
{
	vtkDataArray *a = find(r, where, name);
	return a ? a->GetComponent(tuple, comp) : NAN;
}

extern "C" int vtkr_png(const char *path, int *width, int *height, long *colours,
                        const unsigned *rgb, long *count, int n)
{
	vtkNew<vtkPNGReader> rd;
	if (!rd->CanReadFile(path))
		return -1;
	rd->SetFileName(path);
	rd->Update();
	vtkImageData *img = rd->GetOutput();
	int dim[3];
	img->GetDimensions(dim);
	int nc = img->GetNumberOfScalarComponents();
	*width = dim[0];
	*height = dim[1];
	std::set<unsigned> seen;
	for (int k = 0; k < n; k++)
		count[k] = 0;
	for (int y = 0; y < dim[1]; y++)
		for (int x = 0; x < dim[0]; x++) {
			auto *p = static_cast<unsigned char *>(img->GetScalarPointer(x, y, 0));
			unsigned c = nc >= 3 ? (p[0] << 16 | p[1] << 8 | p[2]) : (p[0] * 0x010101u);
			seen.insert(c);
			for (int k = 0; k < n; k++) {
				int dr = std::abs((int)(c >> 16) - (int)(rgb[k] >> 16));
				int dg =
				    std::abs((int)((c >> 8) & 255) - (int)((rgb[k] >> 8) & 255));
				int db = std::abs((int)(c & 255) - (int)(rgb[k] & 255));
				count[k] += dr <= 40 && dg <= 40 && db <= 40;
			}
		}
	*colours = (long)seen.size();
	return 0;
}
