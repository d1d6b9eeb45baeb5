/* test_engine_countvar.c — the collision tally of the engine
 * (sb_engine_set_count_variance) and the variance of a pair kernel's
 * count (sb_engine_pair_stats.ncoll_var): its bookkeeping against an
 * independent tally of the same collisions, a run unchanged by it, and
 * its validity rules (on after collisions, reset, off), and a checkpoint
 * that keeps it. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <smolbridge/engine.h>
#include <smolbridge/stats.h>

#include "engine_same.h"
#include "testutil.h"

#define NA 40
#define NB 40
#define N (NA + NB)

/* A binary hard-sphere gas (light species 0, heavy species 1), elastic,
 * free flight; seed fixed. */
static sb_engine *gas(void)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 6e-9;
  p.dt = 1e-14;
  p.capacity = N;
  p.seed = 7;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  const double amu = 1.66053907e-27;
  sb_engine_species s0 = {1.4e-10, 4.0 * amu, INFINITY, 0.0, 300.0};
  sb_engine_species s1 = {2.16e-10, 131.3 * amu, INFINITY, 0.0, 300.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s0, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_species(e, &s1, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, NA), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 1, 0, NB), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_thermalize(e, 300.0), SB_SUCCESS);
  return e;
}

/* An independent tally: the elastic outcome, and the counts of each
 * particle (by index: no particle is added, removed or reordered here)
 * with each species, and of each pair. */
typedef struct {
  int on;
  double h[N][2];
  double x[N][N];
} tally;

static int tally_elastic(sb_engine *e, const sb_engine_pair *p, double s,
                         void *ctx)
{
  tally *t = ctx;
  if (t->on) {
    const size_t i = p->i, j = p->j;
    t->h[i][j >= NA]++;
    t->h[j][i >= NA]++;
    t->x[i < j ? i : j][i < j ? j : i]++;
  }
  return sb_engine_outcome_elastic(e, p, s);
}

/* The variance of species pair (a, b) from the tally. */
static double tally_variance(const tally *t, int a, int b, double *H)
{
  double S2 = 0.0, sqa = 0.0, sqb = 0.0;
  *H = 0.0;
  for (int i = 0; i < N; i++)
    for (int j = i + 1; j < N; j++) {
      const int si = i >= NA, sj = j >= NA;
      if ((si == a && sj == b) || (si == b && sj == a)) {
        *H += t->x[i][j];
        S2 += t->x[i][j] * t->x[i][j];
      }
    }
  for (int i = 0; i < N; i++) {
    const int si = i >= NA;
    if (a == b && si == a)
      sqa += t->h[i][a] * t->h[i][a];
    else if (a != b && si == a)
      sqa += t->h[i][b] * t->h[i][b];
    else if (a != b && si == b)
      sqb += t->h[i][a] * t->h[i][a];
  }
  const double na = a ? NB : NA, nb = b ? NB : NA;
  if (a == b)
    return sb_pair_count_variance(*H, S2, sqa, na, 0.0, 0.0,
                                  0.5 * na * (na - 1.0));
  return sb_pair_count_variance(*H, S2, sqa, na, sqb, nb, na * nb);
}

/* Bookkeeping: the engine's ncoll_var for the three species pairs equals
 * the independent tally's, after a warm-up and a reset (the engine's
 * holds the collisions since the reset only); some pairs collide more
 * than once. */
START_TEST(test_bookkeeping)
{
  sb_engine *e = gas();
  tally *t = calloc(1, sizeof *t);
  ck_assert_int_eq(sb_engine_set_outcome_fn(e, tally_elastic, t),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_count_variance(e, 1), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(e, 2e-12), SB_SUCCESS);
  sb_engine_reset_counters(e);
  t->on = 1;
  ck_assert_int_eq(sb_engine_run_until(e, 2e-10), SB_SUCCESS);
  double repeats = 0.0;
  for (int a = 0; a < 2; a++)
    for (int b = a; b < 2; b++) {
      sb_engine_pair_stats ps;
      ck_assert_int_eq(sb_engine_pair_kernel(e, a, b, 0.95, &ps),
                       SB_SUCCESS);
      double H;
      const double v = tally_variance(t, a, b, &H);
      ck_assert_msg((double)ps.ncoll == H && H > 100, "pair %d-%d: engine "
                    "%llu collisions, tally %g", a, b,
                    (unsigned long long)ps.ncoll, H);
      ck_assert_rel(ps.ncoll_var, v, 1e-12);
      ck_assert_rel(ps.dispersion, v / H, 1e-12);
      /* the interval: Garwood's widened by sqrt(dispersion) above 1 */
      double lo, hi;
      sb_poisson_ci_dispersed((unsigned long)H, v / H, 0.95, &lo, &hi);
      const double scale = ps.K / H;
      ck_assert_rel(ps.lo, lo * scale, 1e-12);
      ck_assert_rel(ps.hi, hi * scale, 1e-12);
    }
  for (int i = 0; i < N; i++)
    for (int j = i + 1; j < N; j++)
      repeats += t->x[i][j] > 1.0;
  ck_assert(repeats > 0);
  free(t);
  sb_engine_free(e);
}
END_TEST

/* The tally does not change the run; it is valid only when it holds every
 * collision since the reset; off, no estimate. */
START_TEST(test_rules)
{
  sb_engine *a = gas(), *b = gas();
  ck_assert_int_eq(sb_engine_set_count_variance(a, 1), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(a, 1e-11), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(b, 1e-11), SB_SUCCESS);
  sb_engine_pair_stats pa, pb;
  ck_assert_int_eq(sb_engine_pair_kernel(a, 0, 1, 0.95, &pa), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_pair_kernel(b, 0, 1, 0.95, &pb), SB_SUCCESS);
  ck_assert_uint_eq(pa.ncoll, pb.ncoll);
  ck_assert(pa.K == pb.K && pa.ncoll > 0);
  ck_assert(isfinite(pa.ncoll_var) && isnan(pb.ncoll_var) &&
            isnan(pb.dispersion));
  double lo, hi;  /* without the tally: the plain Garwood interval */
  sb_poisson_rate_ci((unsigned long)pb.ncoll, pb.K / (double)pb.ncoll,
                     0.95, &lo, &hi);
  ck_assert_rel(pb.lo, lo, 1e-14);
  ck_assert_rel(pb.hi, hi, 1e-14);
  /* on after collisions: incomplete until the next reset */
  ck_assert_int_eq(sb_engine_set_count_variance(b, 1), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(b, 1.5e-11), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_pair_kernel(b, 0, 1, 0.95, &pb), SB_SUCCESS);
  ck_assert(isnan(pb.ncoll_var));
  sb_engine_reset_counters(b);
  ck_assert_int_eq(sb_engine_run_until(b, 2.5e-11), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_pair_kernel(b, 0, 1, 0.95, &pb), SB_SUCCESS);
  ck_assert(pb.ncoll > 0 && isfinite(pb.ncoll_var));
  /* off: freed, no estimate */
  ck_assert_int_eq(sb_engine_set_count_variance(b, 0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_pair_kernel(b, 0, 1, 0.95, &pb), SB_SUCCESS);
  ck_assert(isnan(pb.ncoll_var));
  ck_assert_int_eq(sb_engine_set_count_variance(NULL, 1), SB_EINVAL);
  sb_engine_free(a);
  sb_engine_free(b);
}
END_TEST

/* The tally goes through a checkpoint: a run stopped half-way, saved,
 * loaded and run on gives the variance estimates of the run in one go,
 * bit for bit (off in the checkpoint: off after loading; on before any
 * collision: empty tables); a file of the version before (no tally)
 * still loads. */
START_TEST(test_checkpoint)
{
  char path[] = "/tmp/sb_countvar_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  sb_engine *a = gas(), *b = gas();
  /* on, before any collision: empty tables */
  ck_assert_int_eq(sb_engine_set_count_variance(a, 1), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_checkpoint_save(a, path), SB_SUCCESS);
  int st0;
  sb_engine *z = sb_engine_checkpoint_load(path, &st0);
  ck_assert_msg(st0 == SB_SUCCESS, "%s", sb_last_error());
  ck_assert_int_eq(sb_engine_get_count_variance(z), 1);
  sb_engine_free(z);
  for (int k = 0; k < 2; k++) {
    sb_engine *e = k ? b : a;
    ck_assert_int_eq(sb_engine_set_count_variance(e, 1), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_run_until(e, 2e-12), SB_SUCCESS);
    sb_engine_reset_counters(e);
  }
  ck_assert_int_eq(sb_engine_run_until(a, 1e-10), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(b, 5e-11), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_checkpoint_save(b, path), SB_SUCCESS);
  sb_engine_free(b);
  int st;
  b = sb_engine_checkpoint_load(path, &st);
  ck_assert_int_eq(st, SB_SUCCESS);
  ck_assert_int_eq(sb_engine_get_count_variance(b), 1);
  ck_assert_int_eq(sb_engine_run_until(b, 1e-10), SB_SUCCESS);
  for (int p = 0; p < 2; p++)
    for (int q = p; q < 2; q++) {
      sb_engine_pair_stats pa, pb;
      ck_assert_int_eq(sb_engine_pair_kernel(a, p, q, 0.95, &pa),
                       SB_SUCCESS);
      ck_assert_int_eq(sb_engine_pair_kernel(b, p, q, 0.95, &pb),
                       SB_SUCCESS);
      ck_assert_uint_eq(pa.ncoll, pb.ncoll);
      ck_assert_msg(pa.ncoll > 50 && isfinite(pa.ncoll_var) &&
                        pa.ncoll_var == pb.ncoll_var &&
                        pa.lo == pb.lo && pa.hi == pb.hi,
                    "pair %d-%d: %llu collisions, variance %.17g / %.17g",
                    p, q, (unsigned long long)pa.ncoll, pa.ncoll_var,
                    pb.ncoll_var);
    }
  /* off in the checkpoint: off after loading */
  ck_assert_int_eq(sb_engine_set_count_variance(b, 0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_checkpoint_save(b, path), SB_SUCCESS);
  sb_engine *c = sb_engine_checkpoint_load(path, &st);
  ck_assert_int_eq(st, SB_SUCCESS);
  ck_assert_int_eq(sb_engine_get_count_variance(c), 0);
  sb_engine_pair_stats pc;
  ck_assert_int_eq(sb_engine_pair_kernel(c, 0, 1, 0.95, &pc), SB_SUCCESS);
  ck_assert(isnan(pc.ncoll_var));
  ck_assert_int_eq(sb_engine_get_count_variance(NULL), 0);
  /* the file ends in the hash of its contents (version 6): one changed
   * byte, or one byte less, is refused as damaged; without the hash,
   * magic ...5, it loads as version 5; a version 4 file (the same bytes
   * without the block of version 5, magic ...4) still loads, the tally
   * off; one byte more or less does not */
  FILE *f = fopen(path, "rb");
  ck_assert_ptr_nonnull(f);
  fseek(f, 0, SEEK_END);
  const long size = ftell(f);
  rewind(f);
  const long np = SB_ENGINE_PAIR_SPECIES * (SB_ENGINE_PAIR_SPECIES + 1) / 2;
  /* the block of version 5: the Langevin detector's 3 parameters,
   * outflows per face, the inflow slots, their injected and skipped
   * counts, on, lost, 3 sums per pair */
  const long v5 = size - 8;
  const long v4 = v5 - (3 * 8 + 6 * 8 + 4 + 2 * 8 * SB_ENGINE_MAXINFLOW +
                        8 + 24 * np);
  char *buf = malloc((size_t)size);
  ck_assert_ptr_nonnull(buf);
  ck_assert_uint_eq(fread(buf, 1, (size_t)size, f), (size_t)size);
  fclose(f);
  ck_assert(buf[7] == '6');
  for (int k = 0; k < 2; k++) {  /* a byte flipped in the middle, cut */
    buf[size / 2] ^= (char)(k == 0);
    f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    const size_t w = (size_t)(size - k);
    ck_assert_uint_eq(fwrite(buf, 1, w, f), w);
    fclose(f);
    ck_assert_ptr_null(sb_engine_checkpoint_load(path, &st));
    ck_assert_int_eq(st, SB_EFORMAT);
    ck_assert_ptr_nonnull(strstr(sb_last_error(), "damaged"));
    buf[size / 2] ^= (char)(k == 0);
  }
  buf[7] = '5';
  f = fopen(path, "wb");
  ck_assert_ptr_nonnull(f);
  ck_assert_uint_eq(fwrite(buf, 1, (size_t)v5, f), (size_t)v5);
  fclose(f);
  sb_engine *d5 = sb_engine_checkpoint_load(path, &st);
  ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
  sbt_assert_same_run(c, d5, SBT_SAME_CANDIDATES);
  sb_engine_free(d5);
  buf[7] = '4';
  for (int dn = -1; dn <= 1; dn += 2) {  /* a byte short, a byte after */
    f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(buf, 1, (size_t)(v4 + dn), f),
                      (size_t)(v4 + dn));
    fclose(f);
    ck_assert_ptr_null(sb_engine_checkpoint_load(path, &st));
    ck_assert_int_eq(st, SB_EFORMAT);
  }
  f = fopen(path, "wb");
  ck_assert_ptr_nonnull(f);
  ck_assert_uint_eq(fwrite(buf, 1, (size_t)v4, f), (size_t)v4);
  fclose(f);
  free(buf);
  sb_engine *d = sb_engine_checkpoint_load(path, &st);
  ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
  ck_assert_int_eq(sb_engine_get_count_variance(d), 0);
  sbt_assert_same_run(c, d, SBT_SAME_CANDIDATES);
  sb_engine_free(d);
  remove(path);
  sb_engine_free(a);
  sb_engine_free(b);
  sb_engine_free(c);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_countvar");
  TCase *tc = tcase_create("core");
  tcase_add_test(tc, test_bookkeeping);
  tcase_add_test(tc, test_rules);
  tcase_add_test(tc, test_checkpoint);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
