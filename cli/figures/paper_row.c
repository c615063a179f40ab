/* Which row of the paper's Table 1 a setup is, for the figures and films
 * that mark the printed and measured jump points beside the model's. */
#include "figures.h"

#include <math.h>

/* The paper's table is for the paper's cylinder: its body, its printed d and
 * its g. Friction, restitution and the start do not enter the paper's model,
 * so they may differ. */
static int is_paper_cylinder(const jc_Setup *s)
{
    const jc_Setup p = jc_paper_setup();
    return jc_paper_body_is(&s->body) && s->paper_cm_offset_m == p.paper_cm_offset_m &&
           s->gravity_mps2 == p.gravity_mps2;
}

const jc_PaperTableRow *cli_paper_row(const jc_Setup *s)
{
    if (!is_paper_cylinder(s)) return NULL;
    const jc_PaperTableRow *rows;
    const int n = jc_paper_table(&rows);
    for (int i = 0; i < n; ++i)
        if (fabs(cli_deg(s->incline_rad) - rows[i].incline_deg) < 1e-9) return &rows[i];
    return NULL;
}
