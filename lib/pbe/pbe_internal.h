/* pbe_internal.h — the population-balance solver object, shared by
 * lib/pbe/pbe.c (driver, discrete method), lib/pbe/pbe_sectional.c (fixed pivot)
 * and lib/pbe/pbe_fft.c (separable kernels: convolution gain term).  Not
 * installed. */
#ifndef SB_PBE_INTERNAL_H
#define SB_PBE_INTERNAL_H

#include <smolbridge/pbe.h>

/* Sectional gain by diagonals d = k - j of the pair (j, k), j <= k.  On a
 * geometric grid x_k (1 + r^-d) falls between pivots i = k + off and
 * i + 1 with the fraction eta to i whatever k is (scale invariance), so
 * one diagonal is a contiguous loop over j. */
typedef struct {
  unsigned off;   /* target pivot i = j + d + off */
  unsigned cnt;   /* pairs j = 0..cnt-1 stay on the grid */
  double eta;     /* fraction to pivot i (1 - eta to i + 1) */
  size_t start;   /* offset of this diagonal in sb_pbe.kdiag */
} sbi_pbe_diag;

struct sb_pbe {
  sb_pbe_config cfg;
  size_t n;          /* bins */
  size_t ny;         /* ODE size: n, or n + 2 with the lumped tail
                        (y[n] its number, y[n+1] its mass) */
  int tail;          /* discrete method with the lumped tail */
  double *v;         /* volumes (sizes or pivots) */
  double *kmat;      /* n x n kernel matrix, row-major, symmetric (or NULL) */
  double *y0;        /* initial state (ny) */
  double *y;         /* current state (ny) */
  double *work;      /* n doubles: loss rates */
  double *src;       /* n doubles: source buffer */
  double *gbuf;      /* 2n doubles: discrete gain by total index s = i0+j0 */
  double *ktail;     /* n doubles: K(v_a, vbar) with the tail */
  double *dktail;    /* n doubles: dK(v_a, vbar)/dvbar */
  double *pdiag;     /* ny doubles: diagonal of J (preconditioner) */
  double *jtmp;      /* ny doubles: jtimes scratch */
  /* separable built-in kernel (discrete method): 0 none, else
   * 1 + sb_pbe_kernel_kind, coefficient sepK */
  int sep;
  double sepK;
  int use_fft;       /* gain by FFT convolution (pbe_fft.c) */
  int fft_auto;      /* gain AUTO chose the FFT at allocation; a solve
                        with atol below its noise floor uses direct sums */
  size_t nfft;       /* padded length (power of 2 >= 2n - 1) */
  double *fa, *fb;   /* nfft doubles each */
  void *fft;         /* GSL wavetables and workspace (pbe_fft.c) */
  double of_dn, of_dm; /* FFT path: number and volume rates leaving the
                          grid (g[s], s >= n - 1, is not used) */
  /* sectional */
  sbi_pbe_diag *diags;
  size_t ndiag;
  double *kdiag;     /* packed diagonals: (1 - delta_d0/2) K(x_j, x_{j+d}) */
  int have_init;
  char cvmsg[256];   /* last CVODE error message */
};

/* Sectional method (pbe_sectional.c). */
int sbi_pbe_sect_setup(sb_pbe *p);
void sbi_pbe_sect_gain(const sb_pbe *p, const double *n, double *dndt);
/* Add d(gain)/dn to the dense column-major matrix J (leading dim n). */
void sbi_pbe_sect_gain_jac(const sb_pbe *p, const double *n, double *J,
                           size_t ld);
int sbi_pbe_sect_init_exp(sb_pbe *p, double n0, double v0);
/* Add the diagonal of d(gain)/dn to diag[0..n-1]. */
void sbi_pbe_sect_gain_jac_diag(const sb_pbe *p, const double *n,
                                double *diag);

/* Separable kernels (pbe_fft.c).  sbi_pbe_sep_detect sets p->sep/sepK;
 * sbi_pbe_sep_setup allocates the FFT buffers if p->use_fft. */
void sbi_pbe_sep_detect(sb_pbe *p);
int sbi_pbe_sep_setup(sb_pbe *p);
void sbi_pbe_fft_free(sb_pbe *p);
/* Gain by total index: g[s] = 1/2 sum_{i0+j0=s} K n_i0 n_j0, s = 0..2n-2,
 * and loss rates L_i = sum_j K_ij n_j (grid only) into p->work (g NULL:
 * the loss rates only). */
void sbi_pbe_sep_gain_loss(sb_pbe *p, const double *n, double *g);

#endif /* SB_PBE_INTERNAL_H */
