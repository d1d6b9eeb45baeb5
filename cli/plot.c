/* plot.c — sbv_plot: data + gnuplot script for a validation case, rendered
 * to PNG when gnuplot is on PATH (it is optional: the data and the script
 * are always written, so a plot can be made later). */
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <smolbridge/common.h>
#include "cases.h"

/* Is there an executable `name` on PATH? */
static int on_path(const char *name)
{
  const char *path = getenv("PATH");
  if (!path)
    return 0;
  char buf[4096];
  while (*path) {
    size_t n = strcspn(path, ":");
    if (n > 0 && n + strlen(name) + 2 < sizeof buf) {
      memcpy(buf, path, n);
      buf[n] = '/';
      strcpy(buf + n + 1, name);
      if (access(buf, X_OK) == 0)
        return 1;
    }
    path += n;
    if (*path == ':')
      path++;
  }
  return 0;
}

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
  char dat[1024], gp[1024], png[1024];
  snprintf(dat, sizeof dat, "%s/%s.dat", ctx->outdir, name);
  snprintf(gp, sizeof gp, "%s/%s.gp", ctx->outdir, name);
  snprintf(png, sizeof png, "%s.png", name);

  FILE *f = fopen(dat, "w");
  if (!f)
    return SB_EIO;
  fprintf(f, "# %s\n# %s\n", title, header ? header : "");
  for (size_t i = 0; i < nrows; i++)
    for (size_t j = 0; j < ncols; j++)
      fprintf(f, "%.10g%c", data[i * ncols + j], j + 1 < ncols ? ' ' : '\n');
  if (fclose(f) != 0)
    return SB_EIO;

  char datfile[512];
  snprintf(datfile, sizeof datfile, "%s.dat", name);
  f = fopen(gp, "w");
  if (!f)
    return SB_EIO;
  fprintf(f, "# gnuplot script written by smolbridge validate; run it in "
             "this directory.\n");
  fprintf(f, "set terminal pngcairo size 960,640 noenhanced\n");
  fprintf(f, "set output '%s'\nset title '%s'\nset grid\n", png,
          title);
  put_body(f, gnuplot_body, datfile);
  if (fclose(f) != 0)
    return SB_EIO;

  int rendered = 0;
  if (on_path("gnuplot")) {
    char cmd[2300];
    snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot '%s.gp' 2>/dev/null",
             ctx->outdir, name);
    rendered = system(cmd) == 0;
  }
  if (rendered)
    sbv_note(rep, "![%s](%s)", title, png);
  else
    sbv_note(rep, "Plot data `%s.dat`, script `%s.gp` (gnuplot not found: "
                  "run the script to render it).", name, name);
  return SB_SUCCESS;
}
