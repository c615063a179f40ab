/* Which row of the paper's Table 1 a setup is, for the figures and films
 * that mark the printed and measured jump points beside the model's. */
#include "figures.h"

#include <math.h>

int cli_is_paper_body(const jc_BodyDef *body)
{
    const jc_BodyDef p = jc_paper_setup().body;
    if (body->radius_m != p.radius_m || body->part_count != p.part_count) return 0;
    for (int i = 0; i < p.part_count; ++i) {
        const jc_Part *a = &body->parts[i], *b = &p.parts[i];
        if (a->kind != b->kind || a->mass_kg != b->mass_kg || a->offset_m != b->offset_m ||
            a->angle_rad != b->angle_rad || a->radius_m != b->radius_m)
            return 0;
    }
    return 1;
}

/* The paper's table is for the paper's cylinder: its body, its printed d and
 * its g. Friction, restitution and the start do not enter the paper's model,
 * so they may differ. */
static int is_paper_cylinder(const jc_Setup *s)
{
    const jc_Setup p = jc_paper_setup();
    return cli_is_paper_body(&s->body) && s->paper_cm_offset_m == p.paper_cm_offset_m &&
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
