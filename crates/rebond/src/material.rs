//! Surface materials: how two touching surfaces' friction coefficients, restitutions and rolling
//! resistances combine into the one each contact uses.

/// How two values, one from each surface, combine into the contact's value. Every rule gives `v`
/// for two equal values `v`, except [`CombineRule::Multiply`] (`v²`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum CombineRule {
    /// `√(a b)`: a frictionless surface makes the contact frictionless. The default for friction
    /// (Box2D's and Box3D's).
    #[default]
    GeometricMean,
    /// `(a + b) / 2`.
    Average,
    /// `min(a, b)`.
    Min,
    /// `max(a, b)`: a bouncy ball bounces on anything. The default for restitution.
    Max,
    /// `a b`.
    Multiply,
}

impl CombineRule {
    /// The contact's value from the two surfaces' values.
    pub fn combine(self, a: f32, b: f32) -> f32 {
        match self {
            Self::GeometricMean => (a * b).sqrt(),
            Self::Average => 0.5 * (a + b),
            Self::Min => a.min(b),
            Self::Max => a.max(b),
            Self::Multiply => a * b,
        }
    }
}

/// The surface material of a body, or of a compound's child.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Material {
    /// Coulomb friction coefficient, ≥ 0.
    pub friction: f32,
    /// Coefficient of restitution, 0 to 1.
    pub restitution: f32,
    /// Rolling resistance coefficient `c`, ≥ 0, dimensionless: the resisting torque is at most
    /// `c R N` (`solver/rolling.rs`).
    pub rolling_resistance: f32,
    /// The lever `R` of the rolling resistance, m: the radius the surface rolls on
    /// ([`crate::Shape::rolling_radius`]).
    pub rolling_radius: f32,
}

impl Material {
    /// No friction, no bounce: what a contact holds until the world gives it its material.
    pub const NONE: Self = Self {
        friction: 0.0,
        restitution: 0.0,
        rolling_resistance: 0.0,
        rolling_radius: 0.0,
    };

    /// The material of a contact between surfaces `a` and `b`. The rolling resistance and its
    /// lever are each the larger of the two (Box3D's rule): a ball with rolling resistance slows
    /// on any ground, whose own coefficient is most often left at 0, and a box on a ball rolls on
    /// the ball's radius.
    pub fn combine(a: Self, b: Self, friction: CombineRule, restitution: CombineRule) -> Self {
        Self {
            friction: friction.combine(a.friction, b.friction),
            restitution: restitution.combine(a.restitution, b.restitution),
            rolling_resistance: a.rolling_resistance.max(b.rolling_resistance),
            rolling_radius: a.rolling_radius.max(b.rolling_radius),
        }
    }

    /// The most rolling resistance torque per newton of normal force, `c R`, m; zero where the
    /// contact has none.
    pub fn rolling_lever(&self) -> f32 {
        self.rolling_resistance * self.rolling_radius
    }
}

#[cfg(test)]
mod tests {
    use super::CombineRule;

    #[test]
    fn every_rule_combines_as_documented() {
        let cases = [
            (CombineRule::GeometricMean, 0.4),
            (CombineRule::Average, 0.5),
            (CombineRule::Min, 0.2),
            (CombineRule::Max, 0.8),
            (CombineRule::Multiply, 0.16),
        ];
        for (rule, expected) in cases {
            assert!((rule.combine(0.2, 0.8) - expected).abs() < 1e-6, "{rule:?}");
            if rule != CombineRule::Multiply {
                assert_eq!(rule.combine(0.6, 0.6), 0.6, "{rule:?} of equal values");
            }
        }
    }
}
