/* plot.c — sbv_plot: data + gnuplot script for a validation case.  The
 * library writes both files and leaves rendering to the caller's render
 * callback (the command-line tool runs gnuplot), so a plot can always be
 * made later from the files. */
#include <stdlib.h>
#include <string.h>

#include <smolbridge/common.h>
#include "common/internal.h"
#include "cases.h"

/* Copy `body` to f with every "$DATA" replaced by 'file'. */
static void put_body(FILE *f, const char *body, const char *file)
{
  const char *p = body;
  const char *q;
  while ((q = strstr(p, "$DATA")) != NULL) {
    fwrite(p, 1, (size_t)(q - p), f);
    fprintf(f, "'%s'", file);
    p = q + 5;
  }
  fputs(p, f);
  fputc('\n', f);
}

int sbv_plot(const sbv_ctx *ctx, sbv_report *rep, const char *name,
             const char *title, const char *header, const double *data,
             size_t nrows, size_t ncols, const char *gnuplot_body)
{
  if (!ctx->outdir)
    return SB_SUCCESS;
  char dat[1024], gp[1024], png[1024];
  snprintf(dat, sizeof dat, "%s/%s.dat", ctx->outdir, name);
  snprintf(gp, sizeof gp, "%s/%s.gp", ctx->outdir, name);
  snprintf(png, sizeof png, "%s.png", name);

  FILE *f = fopen(dat, "w");
  if (!f)
    return sbi_error(SB_EIO, "sbv_plot", "cannot write '%s'", dat);
  fprintf(f, "# %s\n# %s\n", title, header ? header : "");
  for (size_t i = 0; i < nrows; i++)
    for (size_t j = 0; j < ncols; j++)
      fprintf(f, "%.10g%c", data[i * ncols + j], j + 1 < ncols ? ' ' : '\n');
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, "sbv_plot", "cannot write '%s'", dat);

  char datfile[512];
  snprintf(datfile, sizeof datfile, "%s.dat", name);
  f = fopen(gp, "w");
  if (!f)
    return sbi_error(SB_EIO, "sbv_plot", "cannot write '%s'", gp);
  fprintf(f, "# gnuplot script written by smolbridge validate; run it in "
             "this directory.\n");
  fprintf(f, "set terminal pngcairo size 960,640 noenhanced\n");
  fprintf(f, "set output '%s'\nset title '%s'\nset grid\n", png,
          title);
  put_body(f, gnuplot_body, datfile);
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, "sbv_plot", "cannot write '%s'", gp);

  char script[1040];
  snprintf(script, sizeof script, "%s.gp", name);
  const sb_validate_options *o = ctx->opt;
  int rendered = o && o->render &&
                 o->render(ctx->outdir, script, o->render_data) == 0;
  if (rendered)
    sbv_note(rep, "![%s](%s)", title, png);
  else
    sbv_note(rep, "Plot data `%s.dat`, script `%s.gp` (not rendered: "
                  "run `gnuplot %s.gp` in this directory).", name, name,
             name);
  return SB_SUCCESS;
}
