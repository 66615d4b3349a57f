//! TLS to the broker (`mqtts://`): rustls with the `ring` provider (the build stays free of
//! aws-lc's C toolchain), trusting either the CA certificates of one PEM file (a site's own CA,
//! `--mqtt-ca FILE` or `mqtt: ca_file`) or the system's (Debian's `ca-certificates`). The
//! broker's name is checked against its certificate; there is no way to turn that off.

use std::path::Path;
use std::sync::Arc;

use rustls::pki_types::CertificateDer;
use rustls::pki_types::pem::PemObject;
use rustls::{ClientConfig, RootCertStore};

/// The client configuration trusting `ca_file`'s certificates, or the system's without one.
pub fn client_config(ca_file: Option<&Path>) -> Result<Arc<ClientConfig>, String> {
    let mut roots = RootCertStore::empty();
    match ca_file {
        Some(file) => {
            let certificates = CertificateDer::pem_file_iter(file)
                .map_err(|e| format!("cannot read the CA file {}: {e}", file.display()))?;
            for certificate in certificates {
                let certificate = certificate.map_err(|e| {
                    format!("{} is not a PEM certificate file: {e}", file.display())
                })?;
                roots.add(certificate).map_err(|e| {
                    format!("{} holds a certificate rustls refuses: {e}", file.display())
                })?;
            }
            if roots.is_empty() {
                return Err(format!(
                    "{} holds no certificate (-----BEGIN CERTIFICATE-----)",
                    file.display()
                ));
            }
        }
        None => {
            let found = rustls_native_certs::load_native_certs();
            let (added, _) = roots.add_parsable_certificates(found.certs);
            if added == 0 {
                return Err("no CA certificates found on this system (install Debian's \
                            ca-certificates, or name the broker's CA with --mqtt-ca FILE)"
                    .into());
            }
        }
    }
    let provider = Arc::new(rustls::crypto::ring::default_provider());
    let config = ClientConfig::builder_with_provider(provider)
        .with_safe_default_protocol_versions()
        .map_err(|e| format!("TLS cannot be set up: {e}"))?
        .with_root_certificates(roots)
        .with_no_client_auth();
    Ok(Arc::new(config))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ca_file_that_is_not_there_or_holds_no_certificate_is_said() {
        let missing = client_config(Some(Path::new("/nonexistent/ca.pem"))).unwrap_err();
        assert!(
            missing.contains("cannot read the CA file /nonexistent/ca.pem"),
            "{missing}"
        );
        let dir = tempfile::tempdir().expect("a folder");
        let empty = dir.path().join("empty.pem");
        std::fs::write(&empty, "not a certificate\n").expect("written");
        let none = client_config(Some(&empty)).unwrap_err();
        assert!(none.contains("holds no certificate"), "{none}");
    }
}
