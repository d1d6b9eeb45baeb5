/* eval_dlvo.c — `smolbridge eval` entries of the dlvo module.  Radius
 * r2 = inf selects a sphere–plane pair.  The pair-level entries (energy,
 * force, barrier) take one surface potential psi for both surfaces and a
 * numeric model = vdw + 2 edl (0: Derjaguin + LSA, the model of
 * Mohaupt 2011, §1.2.3;
 * 1: Hamaker + LSA; 2: Derjaguin + HHF; 3: Hamaker + HHF) to stay within
 * the table's argument limit; laws are numbered as sb_dlvo_erel_law. */
#include <math.h>

#include <smolbridge/common.h>
#include <smolbridge/dlvo.h>

#include "cli.h"

SBE_WRAP4(dlvo_debye_kappa)

static int two(int s1, const sb_result *a, int s2, const sb_result *b,
               double *o)
{
  o[0] = a->val;
  o[1] = b->val;
  return s1 != SB_SUCCESS ? s1 : s2;
}

static int w_vdw_hamaker(const double *i, double *o)
{
  sb_result w, f;
  int s1 = sb_dlvo_vdw_hamaker_e(i[0], i[1], i[2], i[3], &w);
  int s2 = sb_dlvo_vdw_hamaker_force_e(i[0], i[1], i[2], i[3], &f);
  return two(s1, &w, s2, &f, o);
}

static int w_vdw_derjaguin(const double *i, double *o)
{
  sb_result w, f;
  int s1 = sb_dlvo_vdw_derjaguin_e(i[0], i[1], i[2], i[3], &w);
  int s2 = sb_dlvo_vdw_derjaguin_force_e(i[0], i[1], i[2], i[3], &f);
  return two(s1, &w, s2, &f, o);
}

static int w_edl_lsa(const double *i, double *o)
{
  sb_result w, f;
  int s1 = sb_dlvo_edl_lsa_e(i[0], i[1], i[2], i[3], i[4], i[5], i[6], i[7],
                             i[8], &w);
  int s2 = sb_dlvo_edl_lsa_force_e(i[0], i[1], i[2], i[3], i[4], i[5], i[6],
                                   i[7], i[8], &f);
  return two(s1, &w, s2, &f, o);
}

static int w_edl_hhf(const double *i, double *o)
{
  sb_result w, f;
  int s1 = sb_dlvo_edl_hhf_e(i[0], i[1], i[2], i[3], i[4], i[5], i[6], &w);
  int s2 = sb_dlvo_edl_hhf_force_e(i[0], i[1], i[2], i[3], i[4], i[5], i[6],
                                   &f);
  return two(s1, &w, s2, &f, o);
}

/* r1 r2 A T eps_r z kappa psi d_contact model -> pair (model checked). */
static int pair_of(const double *i, sb_dlvo_pair *p)
{
  double m = i[9];
  if (!(m == 0 || m == 1 || m == 2 || m == 3))
    return SB_EDOM;
  int mi = (int)m;
  sb_dlvo_pair q = {i[0], i[1], i[2], i[3], i[4], i[5], i[6], i[7], i[7],
                    i[8], (sb_dlvo_vdw_model)(mi & 1),
                    (sb_dlvo_edl_model)(mi >> 1)};
  *p = q;
  return SB_SUCCESS;
}

static int w_energy(const double *i, double *o)
{
  /* args: D r1 r2 A T eps_r z kappa psi model (no d_contact: unused) */
  const double a[10] = {i[1], i[2], i[3], i[4], i[5], i[6], i[7], i[8],
                        1e-10, i[9]};
  sb_dlvo_pair p;
  if (pair_of(a, &p) != SB_SUCCESS)
    return SB_EDOM;
  sb_result w, f;
  int s1 = sb_dlvo_energy_e(&p, i[0], &w);
  int s2 = sb_dlvo_force_e(&p, i[0], &f);
  return two(s1, &w, s2, &f, o);
}

static int w_barrier(const double *i, double *o)
{
  sb_dlvo_pair p;
  if (pair_of(i, &p) != SB_SUCCESS)
    return SB_EDOM;
  sb_dlvo_barrier_t b;
  int s = sb_dlvo_barrier(&p, &b);
  if (s != SB_SUCCESS)
    return s;
  o[0] = b.kind;
  o[1] = b.W_max;
  o[2] = b.D_max;
  o[3] = b.W_max / (1.380649e-23 * p.T);
  o[4] = b.W_min2;
  o[5] = b.D_min2;
  return SB_SUCCESS;
}

/* E theta law dim -> P Q pdf */
static int w_erel_law(const double *i, double *o)
{
  double l = i[2], d = i[3];
  if (!(l == 0 || l == 1 || l == 2 || l == 3) || !(d == 1 || d == 2 || d == 3))
    return SB_EDOM;
  sb_dlvo_erel_law law = (sb_dlvo_erel_law)(int)l;
  sb_result P, Q;
  int s1 = sb_dlvo_erel_P_e(i[0], i[1], law, (int)d, &P);
  int s2 = sb_dlvo_erel_Q_e(i[0], i[1], law, (int)d, &Q);
  o[0] = P.val;
  o[1] = Q.val;
  o[2] = sb_dlvo_erel_pdf(i[0], i[1], law, (int)d);
  o[3] = sb_dlvo_erel_logQ(i[0], i[1], law, (int)d);
  return s1 != SB_SUCCESS ? s1 : s2;
}

/* m1 m2 |v1 - v2| along one axis -> E_rel (App. C eq C.13) */
static int w_erel(const double *i, double *o)
{
  const double v1[3] = {i[2], 0, 0}, v2[3] = {0, 0, 0};
  o[0] = sb_dlvo_erel(i[0], i[1], v1, v2);
  if (!isnan(o[0]))
    return SB_SUCCESS;
  return sb_last_status() != SB_SUCCESS ? sb_last_status() : SB_EDOM;
}

#define WF {"W", "F", NULL}
#define PAIR "r1", "r2", "A", "T", "eps_r", "z", "kappa", "psi", \
             "d_contact", "model"

static const sbe_func funcs[] = {
    {"dlvo_debye_kappa", {"n0", "z", "eps_r", "T", NULL}, {NULL},
     sbe_w_dlvo_debye_kappa, "inverse Debye length of a z:z electrolyte, 1/m"},
    {"dlvo_vdw_hamaker", {"A", "r1", "r2", "D", NULL}, WF, w_vdw_hamaker,
     "full Hamaker vdW energy (J) and force (N); r2=inf: plane"},
    {"dlvo_vdw_derjaguin", {"A", "r1", "r2", "D", NULL}, WF, w_vdw_derjaguin,
     "Derjaguin vdW -A R/(6D) (J) and force (N)"},
    {"dlvo_edl_lsa",
     {"D", "r1", "r2", "kappa", "eps_r", "T", "z", "psi1", "psi2", NULL}, WF,
     w_edl_lsa, "double layer, linear superposition: energy (J), force (N)"},
    {"dlvo_edl_hhf", {"D", "r1", "r2", "kappa", "eps_r", "psi1", "psi2", NULL},
     WF, w_edl_hhf, "double layer, constant potential (HHF): W (J), F (N)"},
    {"dlvo_energy", {"D", "r1", "r2", "A", "T", "eps_r", "z", "kappa", "psi",
                     "model", NULL},
     WF, w_energy,
     "total DLVO W (J), F (N); model 0..3 = vdw + 2 edl, psi1 = psi2 = psi"},
    {"dlvo_barrier", {PAIR, NULL},
     {"kind", "W_max", "D_max", "W_max_kT", "W_min2", "D_min2", NULL},
     w_barrier,
     "energy barrier (kind 0 none, 1 interior, 2 at contact), J and m"},
    {"dlvo_erel_law", {"E", "theta", "law", "dim", NULL},
     {"P", "Q", "pdf", "logQ", NULL}, w_erel_law,
     "laws of E_rel (0 stationary, 1 stat. normal, 2 collision, 3 coll. "
     "normal)"},
    {"dlvo_erel", {"m1", "m2", "w", NULL}, {NULL}, w_erel,
     "relative kinetic energy m1 m2 w^2/(2(m1+m2)), J"},
};

const sbe_table sbe_table_dlvo = {funcs, sizeof funcs / sizeof funcs[0]};
