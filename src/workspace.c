/*
 * A run's working memory: GSL's quadrature workspace (rolling time) and a
 * Brent root solver (root polishing), made once and lent to runs, so that
 * a run itself allocates nothing.
 */
#include "internal.h"

#include <stdlib.h>

jc_Workspace *jc_workspace_new(void)
{
    jc_Workspace *ws = calloc(1, sizeof *ws);
    if (!ws) return NULL;
    ws->quad = gsl_integration_workspace_alloc(JC_QUAD_INTERVALS);
    ws->brent = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!ws->quad || !ws->brent) {
        jc_workspace_free(ws);
        return NULL;
    }
    return ws;
}

void jc_workspace_free(jc_Workspace *ws)
{
    if (!ws) return;
    if (ws->quad) gsl_integration_workspace_free(ws->quad);
    if (ws->brent) gsl_root_fsolver_free(ws->brent);
    free(ws);
}
