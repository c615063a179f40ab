/* Where does the paper's cylinder stop rolling on a 45 degree incline? */
#include <jumpcyl/jumpcyl.h>
#include <stdio.h>

int main(void)
{
    jc_Setup setup = jc_paper_setup();          /* the seed paper's cylinder */
    setup.incline_rad = 45.0 * 3.14159265358979 / 180.0;
    char err[256];
    jc_Model model;
    jc_RollingResult roll;
    if (jc_model_init(&model, &setup, err, sizeof err) != JC_OK ||
        jc_rolling_predict(&model, &roll, err, sizeof err) != JC_OK) {
        fprintf(stderr, "jumpcyl: %s\n", err);
        return 1;
    }
    printf("slips at x = %.2f cm; rolling N = 0 at x = %.2f cm\n",
           roll.slip.state.x_m * 100, roll.liftoff.state.x_m * 100);
    return 0;
}
