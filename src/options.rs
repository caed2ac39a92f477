//! The builder setters of the option types.

/// Implements, on an options type, one `with_<field>` setter per listed
/// field (it takes the field's new value and returns the options), and
/// with `: Default` after the type, `Default` as the type's `DEFAULT`.
macro_rules! setters {
    ($ty:ident: Default { $($body:tt)* }) => {
        $crate::options::setters!($ty { $($body)* });

        impl Default for $ty {
            fn default() -> Self {
                $ty::DEFAULT
            }
        }
    };
    ($ty:ident { $($(#[$doc:meta])* fn $setter:ident($field:ident: $t:ty);)* }) => {
        impl $ty {
            $(
                $(#[$doc])*
                pub fn $setter(mut self, $field: $t) -> Self {
                    self.$field = $field;
                    self
                }
            )*
        }
    };
}

pub(crate) use setters;
