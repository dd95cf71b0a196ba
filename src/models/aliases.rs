//! Type aliases for the common microfacet compositions (documented on [`GgxSmith`]).

use super::CookTorrance;
use crate::fresnel::{Conductor, Dielectric, Schlick};
use crate::masking::SmithHeightCorrelated;
use crate::ndf::{Beckmann, Ggx, GgxIsotropic};

/// Isotropic GGX (the specialized [`GgxIsotropic`]) with the height-correlated Smith
/// masking-shadowing term and any Fresnel term `F`.
///
/// This and the aliases below name the common microfacet compositions, so that a
/// material's type can be written without spelling out [`CookTorrance`]'s five parameters.
///
/// Each name lists the parts the literature names the model by — distribution, masking
/// term, Fresnel term — in that order: "GGX-Smith with Schlick's Fresnel" is the specular
/// term of most real-time engines (B. Karis, "Real Shading in Unreal Engine 4", SIGGRAPH
/// 2013 course; with the height-correlated Smith term of E. Heitz, JCGT 3(2), 2014, as in
/// S. Lagarde, C. de Rousiers, "Moving Frostbite to Physically Based Rendering", 2014, and
/// Filament). All use the exact half-vector square root ([`crate::fast::ExactSqrt`]); the
/// aliases are the types themselves, so `GgxSmithSchlick::new(..)` is
/// [`CookTorrance::new`].
///
/// ```
/// use brdf::models::{GgxSmithConductor, GgxSmithSchlick};
/// use brdf::{fresnel::{Conductor, Schlick}, ior::Preset, masking::SmithHeightCorrelated};
/// use brdf::ndf::GgxIsotropic;
///
/// let plastic: GgxSmithSchlick<f32, 1> =
///     GgxSmithSchlick::new(GgxIsotropic::new(0.3)?, Schlick::new([0.04])?, SmithHeightCorrelated);
/// let gold: GgxSmithConductor<f32> = GgxSmithConductor::new(
///     GgxIsotropic::new(0.2)?,
///     Conductor::from_preset(Preset::Gold)?,
///     SmithHeightCorrelated,
/// );
/// # let _ = (plastic, gold);
/// # Ok::<(), brdf::Error>(())
/// ```
pub type GgxSmith<R, F> = CookTorrance<R, GgxIsotropic<R>, F, SmithHeightCorrelated>;

/// GGX-Smith with Schlick's Fresnel on `N` channels: the real-time standard specular.
pub type GgxSmithSchlick<R, const N: usize> = GgxSmith<R, Schlick<R, N>>;

/// GGX-Smith with the exact RGB conductor Fresnel: a rough metal
/// (`Conductor::from_preset(Preset::Gold)`).
pub type GgxSmithConductor<R> = GgxSmith<R, Conductor<R, 3>>;

/// GGX-Smith with the exact dielectric Fresnel (glass, water, a clear coat). Its channel
/// count is the caller's: `Dielectric` is colourless.
pub type GgxSmithDielectric<R> = GgxSmith<R, Dielectric<R>>;

/// Anisotropic GGX ([`Ggx`], roughness `alpha_x` along the tangent, `alpha_y` along the
/// bitangent) with the height-correlated Smith term and any Fresnel term `F`.
pub type AnisoGgxSmith<R, F> = CookTorrance<R, Ggx<R>, F, SmithHeightCorrelated>;

/// Beckmann (isotropic or anisotropic) with the height-correlated Smith term and any
/// Fresnel term `F`: the original Cook-Torrance distribution.
pub type BeckmannSmith<R, F> = CookTorrance<R, Beckmann<R>, F, SmithHeightCorrelated>;
