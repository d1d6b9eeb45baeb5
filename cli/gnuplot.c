/* gnuplot.c — running gnuplot on a script the command wrote (pbe --plot,
 * validate's plots) without a shell, so that no file name is ever read
 * as shell syntax, and quoting names inside gnuplot scripts. */
#include <fcntl.h>
#include <stdio.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"

int sbc_gnuplot(const char *dir, const char *script)
{
  fflush(NULL);  /* no buffered output duplicated in the child */
  pid_t pid = fork();
  if (pid < 0)
    return -1;
  if (pid == 0) {
    int null = open("/dev/null", O_WRONLY);
    if (null >= 0)
      dup2(null, STDERR_FILENO);
    if (dir && chdir(dir) != 0)
      _exit(126);
    execlp("gnuplot", "gnuplot", script, (char *)NULL);
    _exit(127);
  }
  int status;
  while (waitpid(pid, &status, 0) < 0)
    ;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : -1;
}

void sbc_gnuplot_string(FILE *f, const char *s)
{
  fputc('\'', f);  /* in single quotes a quote is doubled */
  for (; *s; s++) {
    if (*s == '\'')
      fputc('\'', f);
    fputc(*s, f);
  }
  fputc('\'', f);
}
