/* Plain "x y z r" sphere lists: what is written reads back bit for bit;
 * comments and blank lines are skipped; a bad line is one message naming
 * the file and line; nothing is left behind when writing fails. */
#include "tests/check.h"

#include "lib/err.h"
#include "pack/textio.h"

static void write_file(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");
	fputs(text, f);
	fclose(f);
}

static void test_round_trip(void)
{
	enum { N = 1000 };
	double x[3 * N], r[N];
	for (int i = 0; i < N; i++) {
		for (int k = 0; k < 3; k++)
			x[3 * i + k] = sin(1.0 + i * 3 + k) * 1e-2 / 3;
		r[i] = 1e-3 * (0.5 + fabs(cos(i * 0.7)));
	}
	const char *path = check_tmp("spheres.txt");
	CHECK(textio_write(path, x, r, N) == 0);
	double *x2, *r2;
	size_t n;
	CHECK(textio_read(path, &x2, &r2, &n) == 0);
	CHECK(n == N);
	CHECK(memcmp(x, x2, sizeof x) == 0);
	CHECK(memcmp(r, r2, sizeof r) == 0);
	free(x2);
	free(r2);
	FILE *f = fopen(path, "r");
	char head[64];
	CHECK(fgets(head, sizeof head, f) != NULL);
	CHECK_STR(head, "#format x_y_z_r\n");
	fclose(f);
	/* A list written elsewhere: comments, blank lines, tabs, CRLF. */
	write_file(path, "# from Yade\n\n1 2 3 0.5\r\n\t-1e-3 0 2.5e-3\t1e-4\n");
	CHECK(textio_read(path, &x2, &r2, &n) == 0);
	CHECK(n == 2 && x2[3] == -1e-3 && r2[1] == 1e-4 && x2[2] == 3);
	free(x2);
	free(r2);
}

static void bad(const char *text, const char *message)
{
	const char *path = check_tmp("bad.txt");
	write_file(path, text);
	double *x, *r;
	size_t n;
	CHECK(textio_read(path, &x, &r, &n) == -1);
	char want[512];
	snprintf(want, sizeof want, "%s: %s", path, message);
	CHECK_STR(err_msg(), want);
}

static void test_bad_input(void)
{
	bad("1 2 3 0.5\n1 2 x 0.5\n", "line 2: expected four numbers 'x y z r' (m)");
	bad("1 2 3\n", "line 1: expected four numbers 'x y z r' (m)");
	bad("1 2 3 0.5 7\n", "line 1: unexpected '7' after 'x y z r'");
	bad("# header\n1 2 3 -0.5\n", "line 2: radius -0.5: expected a positive radius (m)");
	bad("# nothing\n\n", "no spheres: expected lines 'x y z r' (m)");
	double *x, *r;
	size_t n;
	CHECK(textio_read("no/such/list.txt", &x, &r, &n) == -1);
	CHECK_STR(err_msg(), "no/such/list.txt: cannot open: No such file or directory");
	double one[3] = {0, 0, 0}, rad = 1;
	CHECK(textio_write("no/such/dir/out.txt", one, &rad, 1) == -1);
	CHECK_CONTAINS(err_msg(), "no/such/dir/out.txt: cannot create");
}

int main(void)
{
	test_round_trip();
	test_bad_input();
	return check_done();
}
