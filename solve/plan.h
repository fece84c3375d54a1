/* The loading program weighed against the specimen and the time step at
 * setup (plan.c): what cannot work is refused, what would take hopelessly
 * long is announced, each naming the key that causes it. */
#ifndef DEM_PLAN_H
#define DEM_PLAN_H

typedef struct engine engine;

/* 0, or -1 and err_msg; warnings on stderr unless quiet. */
int plan_check(const engine *e, int quiet);

#endif
