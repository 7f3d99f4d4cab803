"""The plan of a vault (§3.1 input): its model, its validation and its readers."""

from vaultgram.domain.model import Domain, ring_name
from vaultgram.domain.readers import (
    domain_from_3dm,
    domain_from_dict,
    domain_from_dxf,
    domain_from_geojson,
    load_domain,
)
from vaultgram.domain.validation import check_feature_spacing, validate_domain

__all__ = ["Domain", "ring_name", "load_domain", "domain_from_dict", "domain_from_geojson", "domain_from_dxf",
           "domain_from_3dm", "validate_domain", "check_feature_spacing"]
