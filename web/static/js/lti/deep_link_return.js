/**
 * The deep-linking answer page: the form holding the signed LtiDeepLinkingResponse posts itself back to the LMS
 * (without scripts, its button does it).
 */
document.getElementById("lti-return").submit();
